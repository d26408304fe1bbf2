#!/usr/bin/env bash
# Two libraries in one process, round by round: the library of commit A and the working tree's (B), each with the
# shim in-process/Shim.cs compiled against it and loaded into its own AssemblyLoadContext by in-process/Host.cs,
# alternating every simulated second. Against run.sh's alternating processes, both sides here see the same machine
# from one round to the next, so the per-round ratios scatter far less on a loaded host (against the issue's library,
# quartiles 0.60 to 0.66 in one run of 40 rounds, where run.sh's pairs spread 0.44 to 0.69 in one run of 8). A
# defaults to the library issue 13 measured (0.19 s on its machine), so
# 0.19 s x the median ratio is the working tree's time there. Needs git history, the .NET SDK, sed and tar.
#   in-process.sh [rounds] [tolerance B] [tolerance A] [n]     defaults: 40 rounds, 1e-3, 1e-3, 64
#   A=<commit> in-process.sh ...    another library for A;  B=<commit> in-process.sh ...  a commit instead of the working tree
#   RUNNER=2 in-process.sh ...      both sides step on a WorkerThreadRunner(2) of their own library (two threads)
# (The same commit on both sides with two tolerances measures the ratio of the two, as for 1e-6 against 1e-3.)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
A=${A:-460bc80^} # the last commit before the multigrid: the library the issue measured
B=${B:-}
rounds=${1:-40}
tolerance_b=${2:-1e-3}
tolerance_a=${3:-1e-3}
n=${4:-64}
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# shellcheck source=build.sh
. "$here/build.sh"
# Each side's shim is the assembly Shim, which Host.cs loads from the side's folder.
library_a=$(library_project a "$A")
library_b=$(library_project b "$B")
build_program a Library "$library_a" "$here/in-process/Shim.cs" Shim
build_program b Library "$library_b" "$here/in-process/Shim.cs" Shim
build_program Host Exe "" "$here/in-process/Host.cs"
echo "A: ${A}, B: ${B:-the working tree}; $rounds rounds of one simulated second each, $n x $n cloth; load $(cut -d' ' -f1-3 /proc/loadavg)"
dotnet "$work/Host-bin/Host.dll" "$work/a-bin" "$work/b-bin" "$rounds" "$tolerance_a" "$tolerance_b" "$n" | tee "$work/out.txt"
median=$(sed -n 's/.*median \([0-9.]*\),.*/\1/p' "$work/out.txt" | tail -1)
if [ "$A" = "460bc80^" ] && [ "$tolerance_a" = 1e-3 ] && [ "$tolerance_b" = 1e-3 ] && [ "$n" = 64 ]; then
  python3 -c "print(f'on the issue\'s machine (0.19 s there for A): B about {0.19 * $median:.3f} s per simulated second')"
fi
