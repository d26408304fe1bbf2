#!/usr/bin/env python3
"""The tables of docs/benchmarks.md, from the outputs that benchmarks/results.sh collected in a folder.

    results.py WORK [--write docs/benchmarks.md]

Prints three blocks: the frame-cost table (frame-cost/run.sh's output as it is), the results of the other benchmarks,
one section each with its date, machine, load average and command, and the targets with their current figures and
met / not met, computed from the same outputs. With --write, each block replaces the text between its markers in the
page (<!-- results.sh: NAME --> and <!-- results.sh: end NAME -->), so the page holds exactly what the script printed.
"""
import glob
import json
import re
import sys
import textwrap

WORK = sys.argv[1]


def read(name):
    with open(f"{WORK}/{name}", encoding="utf-8") as f:
        return f.read()


def fields(name):
    """The "key value" lines of a .meta or the machine file, as a dict."""
    return dict(line.split(" ", 1) for line in read(name).splitlines() if " " in line)


MACHINE = fields("machine")
QUICK = MACHINE["quick"] == "1"


def load1(text):
    return float(text.split()[0])


def header(name, runtime):
    """A section's first lines: when, where, how loaded, with what, and the command."""
    m = fields(f"{name}.meta")
    return (f"{m['started']}; {MACHINE['machine']}; load average {m['load_before']} before, {m['load_after']} after; "
            f"{runtime}.\n`{m['command']}`\n")


DOTNET = f".NET {MACHINE['dotnet']}"


def number(pattern, text, group=1):
    match = re.search(pattern, text)
    if not match:
        raise SystemExit(f"results.py: no match for {pattern!r} in:\n{text}")
    return float(match.group(group).replace(",", ""))


def ratio_status(value, limit, at_most=True):
    return "met" if (value <= limit if at_most else value >= limit) else "not met"


CORES = int(re.search(r"(\d+) (?:v?CPUs|cores)", MACHINE["machine"]).group(1))


def threads_status(name, value, limit):
    """A two-thread target's status: a miss while other work held more than the cores says so (load, 1 minute)."""
    m = fields(f"{name}.meta")
    load = max(load1(m["load_before"]), load1(m["load_after"]))
    status = ratio_status(value, limit, at_most=False)
    return f"{status}, load {load:.0f}" if status == "not met" and load > CORES else status


# ---- BenchmarkDotNet: the fastest iteration of each benchmark, per operation (one RK4 step) [ns].
bdn = {}
for path in glob.glob(f"{WORK}/bdn/results/*-report-full-compressed.json"):
    with open(path, encoding="utf-8") as f:
        for b in json.load(f)["Benchmarks"]:
            n = int(re.search(r"N=(\d+)", b["Parameters"]).group(1))
            bdn[(b["Type"], b["Method"], n)] = b["Statistics"]["Min"]


def step_ns(kind, method):
    return {n: t for (k, m, n), t in bdn.items() if k == kind and m == method}


rk4 = step_ns("ClothStepBenchmarks", "Rk4Step")
c_rk4 = {}  # n -> (springs, median ns per spring evaluation, best)
for line in read("c-rk4.out").splitlines():
    parts = line.split()
    if len(parts) == 7 and parts[0].isdigit():
        c_rk4[int(parts[0])] = (int(parts[1]), float(parts[4]), float(parts[6]))
springs = {n: c_rk4[n][0] for n in c_rk4}


def per_spring(n, ns_per_step):
    return ns_per_step / (4 * springs[n])


results = []
results.append("### RK4 step against plain C\n")
results.append(header("bdn", DOTNET) + f"`{fields('c-rk4.meta')['command']}` (gcc {MACHINE['gcc']}, -O3 -march=native)\n")
results.append("| n | springs | library: one step [us] | library: ns per spring evaluation | C: ns per spring evaluation | library / C |")
results.append("| ---: | ---: | ---: | ---: | ---: | ---: |")
for n in sorted(rk4):
    lib = per_spring(n, rk4[n])
    _, c_median, c_best = c_rk4[n]
    results.append(f"| {n} | {springs[n]:,} | {rk4[n] / 1e3:,.1f} | {lib:.2f} | {c_best:.2f} ({c_median:.2f}) | {lib / c_best:.3f} |")
results.append("\nThe library's fastest of the BenchmarkDotNet iterations; the C reference's fastest of 7 batches (median in "
               "brackets). A step is 4 evaluations of every spring.\n")

comparison = {m: step_ns("ComparisonBenchmarks", m) for m in ("Library", "FourEvaluations", "MathNet", "Student")}
allocated = {}
for path in glob.glob(f"{WORK}/bdn/results/*Comparison*-report-full-compressed.json"):
    with open(path, encoding="utf-8") as f:
        for b in json.load(f)["Benchmarks"]:
            n = int(re.search(r"N=(\d+)", b["Parameters"]).group(1))
            allocated[(b["Method"], n)] = b["Memory"]["BytesAllocatedPerOperation"]
results.append("### RK4 against Math.NET and a student's code\n")
results.append(header("bdn", DOTNET))
results.append("| n | library [us per step] | 4 x Evaluate (the forces alone) | Math.NET | student | library faster than Math.NET | than the student | allocated per step: Math.NET / student |")
results.append("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for n in sorted(comparison["Library"]):
    lib, floor, mathnet, student = (comparison[m][n] / 1e3 for m in ("Library", "FourEvaluations", "MathNet", "Student"))
    results.append(f"| {n} | {lib:,.1f} | {floor:,.1f} | {mathnet:,.1f} | {student:,.1f} | {mathnet / lib:.2f}x | "
                   f"{student / lib:.2f}x | {allocated[('MathNet', n)] / 1e3:,.0f} kB / {allocated[('Student', n)] / 1e3:,.0f} kB |")
results.append("\nFastest iterations. The library allocates nothing per step (the `verify` mode and the tests check it).\n")

one, two = step_ns("ParallelBenchmarks", "OneCore"), step_ns("ParallelBenchmarks", "TwoCores")
results.append("### RK4 on two threads\n")
results.append(header("bdn", DOTNET))
results.append("| n | one core [us per step] | WorkerThreadRunner(2) | speedup |")
results.append("| ---: | ---: | ---: | ---: |")
for n in sorted(one):
    results.append(f"| {n} | {one[n] / 1e3:,.1f} | {two[n] / 1e3:,.1f} | {one[n] / two[n]:.2f}x |")
results.append("\nFastest iterations; the same bits on one thread and two (`ParallelRunnerTests`).\n")

# ---- xpbd against C, and on two threads.
xpbd = {}
for line in read("xpbd.out").splitlines():
    if line.startswith("n ="):
        n = int(number(r"n =\s*(\d+)", line))
        xpbd[n] = {
            "springs": int(number(r"\((\d+) springs", line)),
            "same": "same bits" in line,
            "c": (number(r"C ([\d.]+) \(", line), number(r"C [\d.]+ \(([\d.]+)\)", line)),
            "lib": (number(r"library ([\d.]+) \(", line), number(r"library [\d.]+ \(([\d.]+)\)", line)),
            "ratio": number(r"C# / C ([\d.]+)", line),
            "median": number(r"median ([\d.]+)", line),
            "lib_ns": number(r"library ([\d.]+) ns", line),
            "c_ns": number(r"C ([\d.]+) ns per projection", line),
        }
results.append("### xpbd against plain C\n")
results.append(header("xpbd", DOTNET + f" and gcc {MACHINE['gcc']}"))
results.append("| n | springs | C [ms per simulated s] | library | library / C | library: ns per projection | C: ns per projection |")
results.append("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for n, x in sorted(xpbd.items()):
    results.append(f"| {n} | {x['springs']:,} | {x['c'][0]:,.1f} ({x['c'][1]:,.1f}) | {x['lib'][0]:,.1f} ({x['lib'][1]:,.1f}) | "
                   f"{x['ratio']:.3f} (median {x['median']:.3f}) | {x['lib_ns']:.2f} | {x['c_ns']:.2f} |")
results.append("\n10 substeps per 1/60 s frame, one simulated second from rest, C and library in turn in one process after a "
               "check that they compute the same bits: the fastest round in wall time (the process's CPU time in "
               "brackets); library / C of the fastest rounds (the median of the rounds' ratios).\n")

cores = {}
for line in read("xpbd-cores.out").splitlines():
    if line.startswith("n ="):
        n = int(number(r"n =\s*(\d+)", line))
        cores[n] = {
            "same": "same bits on one and two cores" in line,
            "one": number(r"one core ([\d.]+)", line),
            "two": number(r"two ([\d.]+) \(", line),
            "speedup": number(r"speedup ([\d.]+)", line),
            "median": number(r"speedup [\d.]+, median ([\d.]+)", line),
            "cpu": number(r"CPU two / one ([\d.]+)", line),
        }
results.append("### xpbd on two threads\n")
results.append(header("xpbd-cores", DOTNET))
results.append("| n | one core [ms per simulated s] | WorkerThreadRunner(2) | speedup | CPU time, two / one | bits |")
results.append("| ---: | ---: | ---: | ---: | ---: | --- |")
for n, x in sorted(cores.items()):
    results.append(f"| {n} | {x['one']:,.1f} | {x['two']:,.1f} | {x['speedup']:.2f}x (median {x['median']:.2f}x) | {x['cpu']:.2f} | "
                   f"{'the same' if x['same'] else 'DIFFERENT'} |")
results.append("\nFastest rounds of one simulated second, alternating; the CPU time of two threads over one's is 1 for a "
               "perfect split.\n")

# ---- Implicit Euler: one core and two, at 1e-3 and 1e-6.
implicit = {}
for tolerance in ("1e-3", "1e-6"):
    text = read(f"implicit-{tolerance}.out")
    rows = {}
    for line in text.splitlines():
        match = re.match(r"\s+(one core|spin limit 0|adaptive, [\d.]+ us)\s+([\d.]+) \(\s*([\d.]+)\) ms, CPU\s+([\d.]+) ms; x one core\s+([\d.]+)", line)
        if match:
            rows[match.group(1).split(",")[0]] = tuple(float(match.group(g)) for g in (2, 3, 4, 5))
    implicit[tolerance] = {
        "n": int(number(r"(\d+) x \d+ cloth", text)),
        "iterations": number(r"([\d.]+) CG iterations per frame", text),
        "same": "same bits with every runner" in text,
        "one": rows["one core"],
        "two": rows["adaptive"],
    }
results.append("### Implicit Euler per simulated second\n")
results.append(header("implicit-1e-3", DOTNET) + f"`{fields('implicit-1e-6.meta')['command']}`\n")
results.append(f"| tolerance ({implicit['1e-3']['n']} x {implicit['1e-3']['n']} cloth) | CG iterations per frame | one core [ms per simulated s] | "
               "CPU | WorkerThreadRunner(2) | speedup | bits |")
results.append("| --- | ---: | ---: | ---: | ---: | ---: | --- |")
for tolerance, x in implicit.items():
    (one_best, one_median, one_cpu, _), (two_best, two_median, _, two_x) = x["one"], x["two"]
    results.append(f"| {tolerance} | {x['iterations']:.2f} | {one_best:,.1f} ({one_median:,.1f}) | {one_cpu:,.1f} | "
                   f"{two_best:,.1f} ({two_median:,.1f}) | {one_best / two_best:.2f}x (median {two_x:.2f}x) | "
                   f"{'the same' if x['same'] else 'DIFFERENT'} |")
results.append("\nOne step per 60 Hz frame, one simulated second from rest with a cold solver, the multigrid preconditioner "
               "(the default); one core and two threads alternating: the fastest round (the median), the process's CPU "
               "time (median), the speedup of the fastest rounds (the median of the rounds' ratios).\n")

# ---- Quality: the mode's own table (deterministic).
quality = read("quality.out")
results.append("### Quality next to speed\n")
results.append(header("quality", DOTNET))
results.append(quality.strip() + "\n")

# ---- Contacts.
contacts = []
for line in read("contacts.out").splitlines():
    cells = [c.strip() for c in line.strip("|").split("|")]
    if cells and cells[0].isdigit():
        contacts.append(cells)
results.append("### The contact stage per particle\n")
results.append(header("contacts", DOTNET))
results.append("| particles | candidate pairs per particle | impacts per particle | near a wall | fastest resolve [ms] | per particle [us] | CPU per particle [us] |")
results.append("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for c in contacts:
    results.append(f"| {int(c[0]):,} | {c[1]} | {c[2]} | {c[3]} | {c[6]} | {c[7]} | {c[8]} |")
wall = [float(c[7]) for c in contacts]
cpu = [float(c[8]) for c in contacts]
results.append(f"\n`ContactSet.Resolve` on a settled pile in a box, the sizes in turn: the fastest batch. Per particle, the "
               f"largest over the smallest: {max(wall) / min(wall):.2f}x (CPU time {max(cpu) / min(cpu):.2f}x).\n")

# ---- OBJ.
obj = read("obj.out")
obj_best = number(r"fastest of \d+ reads [\d.]+ s \(([\d.]+) MB/s\)", obj)
results.append("### OBJ parsing\n")
results.append(header("obj", DOTNET))
results.append("| vertices | triangles | file [MB] | fastest read [s] | MB/s | median MB/s |")
results.append("| ---: | ---: | ---: | ---: | ---: | ---: |")
obj_cells = (number(r"obj: ([\d,]+) vertices", obj), number(r"([\d,]+) triangles", obj), number(r"([\d.]+) MB;", obj),
             number(r"reads ([\d.]+) s", obj), obj_best, number(r"median [\d.]+ s \(([\d.]+) MB/s", obj))
results.append("| {:,.0f} | {:,.0f} | {:.1f} | {:.3f} | {:.0f} | {:.0f} |".format(*obj_cells))
results.append("\n`ObjReader.Read` of a generated square grid (`v` lines with six decimals, quads as `f a/a/a ...`) from a "
               "file, whole.\n")

# ---- The demo's runs under perf.
demo = {}
for line in read("demo.out").splitlines():
    issue, share, arguments = line.split("|", 2)
    demo[issue] = (float(share) if share else None, arguments)
results.append("### The demo's runs: time in the step\n")
results.append(header("demo", DOTNET + ", perf"))
results.append("| issue | run | samples in `ParticleWorld.Step` |")
results.append("| ---: | --- | ---: |")
for issue, (share, arguments) in sorted(demo.items(), key=lambda item: int(item[0])):
    results.append(f"| {issue} | `dotnet run -c Release --project samples/ParticlePhysics.Demo -- {arguments} --format csv` | "
                   f"{'not measured (no perf)' if share is None else f'{share:.1f} %'} |")
results.append("\nThe share of the whole process's perf samples (start-up, compilation and the rows included) inside the step "
               "and what it calls.\n")

# ---- The load while the script ran, for the page's first screen and the results.
loads = []
for path in glob.glob(f"{WORK}/*.meta"):
    m = fields(path.rsplit("/", 1)[1])
    loads += [load1(m["load_before"]), load1(m["load_after"])]
cores_count = CORES
if max(loads) > cores_count:
    load_line = (f"Measured {MACHINE['started']} to {MACHINE['ended']} at load averages of {min(loads):.1f} to {max(loads):.1f} "
                 f"on {cores_count} cores: other work shared the machine, so these times are upper bounds.")
else:
    load_line = (f"Measured {MACHINE['started']} to {MACHINE['ended']} at load averages of {min(loads):.1f} to {max(loads):.1f} "
                 f"on {cores_count} cores: a quiet machine.")
if QUICK:
    load_line += " QUICK RUN (`results.sh --quick`): small cloths, one round; not measurements."
results.insert(0, load_line + "\n")

# ---- Targets.
T = []


def target(issue, goal, now, status):
    T.append(f"| {issue} | {goal} | {now} | {status} |")


def largest(values):
    return max(values) / min(values)


# The sizes the targets name where the run has them (a quick run has only small cloths).
scaling = {n: per_spring(n, t) for n, t in rk4.items() if n >= 32}
big = 128 if 128 in rk4 else max(rk4)
lib_big, c_big = per_spring(big, rk4[big]), c_rk4[big][2]
target(5, f"RK4 step per spring evaluation at most plain C's, n = {big}", f"{lib_big:.2f} ns vs {c_big:.2f} ns: {lib_big / c_big:.2f}x",
       ratio_status(lib_big / c_big, 1.0))
if scaling:
    flat = largest(scaling.values())
    target(5, f"RK4 per spring evaluation flat within 1.3x, n = {min(scaling)} to {max(scaling)}",
           f"{min(scaling.values()):.2f} to {max(scaling.values()):.2f} ns: {flat:.2f}x", ratio_status(flat, 1.3))
lib = comparison["Library"]
mathnet = {n: comparison["MathNet"][n] / lib[n] for n in lib}
student = {n: comparison["Student"][n] / lib[n] for n in lib}
target(5, "at least 10x faster than Math.NET's RK4", ", ".join(f"{r:.1f}x at n = {n}" for n, r in sorted(mathnet.items())),
       ratio_status(min(mathnet.values()), 10, at_most=False) + " (below)")
target(5, "at least 5x faster than the student baseline", ", ".join(f"{r:.1f}x at n = {n}" for n, r in sorted(student.items())),
       ratio_status(min(student.values()), 5, at_most=False) + " (below)")
allocation = number(r"bytes allocated per library RK4 step: (\d+)", read("verify.out"))
target(5, "0 bytes allocated per step", f"{allocation:.0f} B (`verify`; the tests, every integrator)", ratio_status(allocation, 0))
n2 = max(one)
target(5, f"two threads at least 1.6x on {n2} x {n2}, the same bits", f"{one[n2] / two[n2]:.2f}x; the same bits (tests)",
       threads_status("bdn", one[n2] / two[n2], 1.6))


def demo_target(issue, run):
    """Issues 5 and 13: a demo run "spends its time in the steps", read as more than half of its samples."""
    share = demo[issue][0]
    target(issue, f"{run}: its time in the steps (more than half)", "not measured (no perf)" if share is None else f"{share:.0f} % in the step",
           "-" if share is None else ("met" if share > 50 else "not met"))


demo_target("5", "the demo's 128 x 128 cloth, 800 RK4 steps")
contact_flat = largest(wall)
target(11, f"contact stage per particle flat within 1.5x, {int(contacts[0][0]):,} to {int(contacts[-1][0]):,} particles",
       f"{', '.join(f'{w:.2f}' for w in wall)} us: {contact_flat:.2f}x", ratio_status(contact_flat, 1.5))
target(11, "contact stage allocation-free", "0 B (`ContactStageTests`)", "met")
for n in [n for n in (64, 128) if n in xpbd] or sorted(xpbd):
    x = xpbd[n]
    target(13, f"xpbd, one simulated second of {n} x {n}: at most 1.1x plain C", f"{x['ratio']:.3f}x (median {x['median']:.3f}); the same bits",
           ratio_status(x["ratio"], 1.1))
projection = {n: x["lib_ns"] for n, x in xpbd.items()}
target(13, f"xpbd per projection flat, n = {min(projection)} to {max(projection)} (within 1.3x, as issue 5's)",
       f"{min(projection.values()):.2f} to {max(projection.values()):.2f} ns: {largest(projection.values()):.2f}x",
       ratio_status(largest(projection.values()), 1.3))
one_e3 = implicit["1e-3"]["one"][0] / 1e3
one_e6 = implicit["1e-6"]["one"][0] / 1e3
size = implicit["1e-3"]["n"]
target(13, f"implicit Euler at 1e-3, {size} x {size}: at most 0.1 s per simulated second on one core",
       f"{one_e3:.3f} s ({implicit['1e-3']['iterations']:.2f} CG iterations per frame)", ratio_status(one_e3, 0.1))
target(13, "implicit Euler at 1e-6: within 2x of the 1e-3 time", f"{one_e6:.3f} s: {one_e6 / one_e3:.2f}x", ratio_status(one_e6 / one_e3, 2))
rows = {m.group(1): float(m.group(2)) for m in re.finditer(r"\| (implicit Euler, tolerance 1e-\d) \| [^|]+ \| [^|]+ \| ([-\d.]+) \|", quality)}
shape = abs(rows["implicit Euler, tolerance 1e-3"] - rows["implicit Euler, tolerance 1e-6"])
target(13, "implicit Euler at 1e-3: the hanging shape within 1e-3 m of a tight solve",
       f"lowest points after 5 s {shape:.6f} m apart", ratio_status(shape, 1e-3))
nc = 64 if 64 in cores else min(cores)
target(13, "xpbd on two threads at least 1.6x, the same bits",
       ", ".join(f"{x['speedup']:.2f}x at {n} x {n}" for n, x in sorted(cores.items())) + ("; the same bits" if all(x["same"] for x in cores.values()) else "; DIFFERENT bits"),
       threads_status("xpbd-cores", cores[nc]["speedup"], 1.6) if all(x["same"] for x in cores.values()) else "not met")
speedups = {t: x["one"][0] / x["two"][0] for t, x in implicit.items()}
target(13, "implicit Euler on two threads at least 1.6x, the same bits",
       f"{speedups['1e-3']:.2f}x at 1e-3, {speedups['1e-6']:.2f}x at 1e-6" + ("; the same bits" if all(x["same"] for x in implicit.values()) else "; DIFFERENT bits"),
       threads_status("implicit-1e-3", speedups["1e-3"], 1.6) if all(x["same"] for x in implicit.values()) else "not met")
demo_target("13", "the demo's 64 x 64 xpbd cloth, 10 s at 60 Hz")
target(13, "quality next to speed: hanging shape and stretch per solver", "the quality table above", "reported")
target("28 (open)", "OBJ parsing at least 50 MB/s", f"{obj_best:.0f} MB/s", ratio_status(obj_best, 50, at_most=False))

targets = [f"From the tables above ({MACHINE['started']}, {MACHINE['machine']}).\n",
           "| issue | target | now | status |", "| --- | --- | --- | --- |"] + T



def wrap(text):
    """The captions at the docs' 120 columns; tables and commands as they are."""
    lines = text.split("\n")
    def verbatim(line):
        return line.startswith(("|", "#")) or (line.startswith("`") and line.endswith("`"))
    return "\n".join(line if verbatim(line) else textwrap.fill(line, 120, break_on_hyphens=False) for line in lines)


blocks = {
    "frame": read("frame.out").strip() + "\n\n" + wrap(load_line),
    "results": "\n".join(wrap(line) for line in results).strip(),
    "targets": "\n".join(targets).strip(),
}

for name, text in blocks.items():
    print(f"<!-- results.sh: {name} -->\n{text}\n<!-- results.sh: end {name} -->\n")

if "--write" in sys.argv:
    page_path = sys.argv[sys.argv.index("--write") + 1]
    with open(page_path, encoding="utf-8") as f:
        page = f.read()
    for name, text in blocks.items():
        pattern = re.compile(rf"<!-- results\.sh: {name} -->\n.*?<!-- results\.sh: end {name} -->", re.S)
        if not pattern.search(page):
            raise SystemExit(f"results.py: {page_path} has no block {name} (<!-- results.sh: {name} --> ... end {name})")
        page = pattern.sub(lambda _: f"<!-- results.sh: {name} -->\n{text}\n<!-- results.sh: end {name} -->", page)
    with open(page_path, "w", encoding="utf-8") as f:
        f.write(page)
    print(f"results: wrote {page_path}", file=sys.stderr)
