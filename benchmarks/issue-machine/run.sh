#!/usr/bin/env bash
# How fast this machine is against the one issue 13's figures were measured on, by the same code: the issue's
# implicit-Euler second (64 x 64 cloth, 60 Hz, tolerance 1e-3) took 0.19 s there with the library of commit THEN
# (block Jacobi, 24 CG iterations per step). This builds that library (git archive of THEN) and the working tree's,
# runs Program.cs against each in turn, alternating, and prints each run and the ratio now / then, so that
# 0.19 s x ratio is the working tree's time on the issue's machine. Needs git history (a full clone), the .NET SDK,
# python3, sed and tar. The two small programs are built in a temporary folder: they reference only the libraries,
# which need no package.
#   run.sh [pairs] [rounds]      pairs of alternating processes (default 4), timed rounds per process (default 7)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
THEN=${THEN:-460bc80^} # the last commit before the multigrid: the library the issue measured
pairs=${1:-4}
rounds=${2:-7}
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# shellcheck source=build.sh
. "$here/build.sh"
then_library=$(library_project then "$THEN")
now_library=$(library_project now "")
build_program then-app Exe "$then_library" "$here/Program.cs"
build_program now-app Exe "$now_library" "$here/Program.cs"
thens=()
nows=()
for ((i = 1; i <= pairs; i++)); do
  then_line=$(LABEL="then ($THEN)" dotnet "$work/then-app-bin/then-app.dll" "$rounds")
  now_line=$(LABEL="now" dotnet "$work/now-app-bin/now-app.dll" "$rounds")
  echo "$then_line"
  echo "$now_line"
  t=$(sed -E 's/.*fastest ([0-9.]+) ms.*/\1/' <<< "$then_line")
  n=$(sed -E 's/.*fastest ([0-9.]+) ms.*/\1/' <<< "$now_line")
  thens+=("$t")
  nows+=("$n")
done
python3 - "${thens[*]}" "${nows[*]}" <<'PY'
import statistics, sys
then = [float(x) for x in sys.argv[1].split()]
now = [float(x) for x in sys.argv[2].split()]
r = sorted(n / t for t, n in zip(then, now))
m = statistics.median(r)
best = min(now) / min(then)
print(f"now / then, fastest rounds of each pair: {' '.join(f'{x:.3f}' for x in r)}; median {m:.3f}")
print(f"fastest round of all: then {min(then):.1f} ms, now {min(now):.1f} ms: {best:.3f}")
print(f"on the issue's machine (then 0.19 s): now about {0.19 * m:.3f} s per simulated second "
      f"(by the fastest rounds of all, {0.19 * best:.3f} s)")
PY
