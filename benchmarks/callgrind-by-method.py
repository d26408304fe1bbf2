#!/usr/bin/env python3
"""Instructions and data-cache misses per method, from two callgrind runs of different lengths.

Usage:
    callgrind-by-method.py SHORT.out SHORT.map LONG.out LONG.map DIVISOR [--top 30]

Each run is `valgrind --tool=callgrind --cache-sim=yes --dump-instr=yes` of a .NET program started with
DOTNET_PerfMapEnabled=1 (and DOTNET_TieredCompilation=0, so that each method is compiled once), whose perf map
(/tmp/perf-PID.map, PID = valgrind's process id) names the JIT-compiled code; native code keeps callgrind's function
name. The self cost of each method in the LONG run minus the SHORT run, divided by DIVISOR (for instance 2 N for
3 and 1 resolves of the contact stage on N particles: start-up, setup and compilation cancel), is printed as
instructions (Ir), L1 data misses (D1mr + D1mw) and last-level data misses (DLmr + DLmw), largest first; from runs
without --cache-sim=yes, instructions and each method's share of them.

Callgrind's format: after `positions: instr line`, a cost line is "address line cost...", where an address or line
may be absolute, relative to the previous one (+n, -n) or the same (*); the line after `calls=` is the inclusive
cost of a call, which this script leaves to the callee (self cost only).
"""
import bisect
import re
import sys
from collections import defaultdict


def load_map(path):
    """The perf map's (start, size, short name) rows, sorted by start."""
    rows = []
    with open(path) as f:
        for line in f:
            parts = line.rstrip('\n').split(' ', 2)
            if len(parts) < 3:
                continue
            match = re.search(r'([A-Za-z0-9_.`]+::[A-Za-z0-9_.<>`|]+)\(', parts[2])
            name = match.group(1) if match else parts[2]
            for prefix in ('ParticlePhysics.Contacts.', 'ParticlePhysics.'):
                name = name.replace(prefix, '')
            rows.append((int(parts[0], 16), int(parts[1], 16), name))
    rows.sort()
    return rows


def self_costs(path, rows):
    """The event names and each method's self cost summed over its instructions."""
    starts = [r[0] for r in rows]
    events, names, totals = None, {}, defaultdict(lambda: None)
    function, address, line, skip = '?', 0, 0, False

    def position(token, previous):
        if token == '*':
            return previous
        if token[0] in '+-':
            return previous + int(token, 0)
        return int(token, 0)

    def method(at):
        k = bisect.bisect_right(starts, at) - 1
        if k >= 0 and at < rows[k][0] + rows[k][1]:
            return rows[k][2]
        return 'native: ' + function

    with open(path) as f:
        for text in f:
            text = text.rstrip('\n')
            if not text:
                continue
            if text[0].isdigit() or text[0] in '+-*':
                tokens = text.split()
                address = position(tokens[0], address)
                line = position(tokens[1], line) if len(tokens) > 1 else line
                if skip:
                    skip = False
                    continue
                name = method(address)
                if totals[name] is None:
                    totals[name] = [0] * len(events)
                for i, value in enumerate(tokens[2:]):
                    totals[name][i] += int(value)
            elif text.startswith('events:'):
                events = text.split()[1:]
            elif text.startswith(('fn=', 'cfn=')):
                match = re.match(r'c?fn=\((\d+)\)(?: (.*))?', text)
                if match:
                    if match.group(2):
                        names[match.group(1)] = match.group(2)
                    if text.startswith('fn='):
                        function = names.get(match.group(1), '?')
                elif text.startswith('fn='):
                    function = text[3:]
            elif text.startswith('calls='):
                skip = True
    return events, {k: v for k, v in totals.items() if v is not None}


def main(argv):
    if len(argv) < 6:
        sys.exit(__doc__)
    top = int(argv[argv.index('--top') + 1]) if '--top' in argv else 30
    events, short = self_costs(argv[1], load_map(argv[2]))
    _, long = self_costs(argv[3], load_map(argv[4]))
    divisor = float(argv[5])
    zero = [0] * len(events)
    difference = {k: [(b - a) / divisor for a, b in zip(short.get(k, zero), long.get(k, zero))]
                  for k in set(short) | set(long)}
    ir = events.index('Ir')
    total = [sum(v[i] for v in difference.values()) for i in range(len(events))]
    rows = [('total', total)] + sorted(difference.items(), key=lambda kv: -abs(kv[1][ir]))[:top]
    if 'D1mr' not in events:  # a run without --cache-sim=yes: instructions only
        print(f"{'method':60} {'Ir':>10} {'share':>7}")
        for name, v in rows:
            print(f'{name[:60]:60} {v[ir]:10.1f} {v[ir] / total[ir]:7.1%}')
        return
    d1, ll = (events.index('D1mr'), events.index('D1mw')), (events.index('DLmr'), events.index('DLmw'))
    print(f"{'method':60} {'Ir':>10} {'L1 miss':>8} {'LL miss':>8}")
    for name, v in rows:
        print(f'{name[:60]:60} {v[ir]:10.1f} {v[d1[0]] + v[d1[1]]:8.2f} {v[ll[0]] + v[ll[1]]:8.2f}')

if __name__ == '__main__':
    main(sys.argv)
