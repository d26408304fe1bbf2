#!/usr/bin/env bash
# What a 60 Hz frame of the 64 x 64 cloth costs per integrator, on .NET and on Mono, one thread and two: the first
# table of docs/benchmarks.md, in one command. Builds FrameCost.cs with the .NET SDK (FrameCost.csproj) and with
# Mono's mcs against the same netstandard2.1 ParticlePhysics.dll, runs it on CoreCLR and on Mono, checks that both
# runtimes computed the same bits, and prints the combined markdown table with the machine, the date and the load.
# Needs the .NET SDK and mono-devel (mono, mcs). About 3 minutes at the defaults on a quiet 2-core machine.
#   run.sh [--rounds 5] [--n 64]
set -euo pipefail
cd "$(dirname "$0")/../.."
export DOTNET_CLI_TELEMETRY_OPTOUT=1 DOTNET_NOLOGO=1 DOTNET_SKIP_FIRST_TIME_EXPERIENCE=1
die() { echo "frame-cost: $*" >&2; exit 1; }

rounds=5
n=64
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds=$2; shift 2 ;;
    --n) n=$2; shift 2 ;;
    *) die "unknown argument $1 (usage: run.sh [--rounds 5] [--n 64])" ;;
  esac
done

facades=/usr/lib/mono/4.5/Facades/netstandard.dll
command -v mono >/dev/null && command -v mcs >/dev/null && [ -f "$facades" ] \
  || die "mono, mcs or $facades is missing: install mono-devel (apt-get install mono-devel)"
work=$(mktemp -d /tmp/pp-frame-cost.XXXXXX)
trap 'rm -rf "$work"' EXIT

dotnet build benchmarks/frame-cost/FrameCost.csproj -c Release --nologo -v quiet >"$work/build.log" 2>&1 \
  || { cat "$work/build.log" >&2; die "dotnet build failed"; }
core=src/ParticlePhysics/bin/Release/netstandard2.1/ParticlePhysics.dll
clr=benchmarks/frame-cost/bin/Release/net10.0
cmp -s "$core" "$clr/ParticlePhysics.dll" || die "the CoreCLR program does not run the built $core"
cp "$core" "$work/"
mcs -langversion:7.2 -optimize+ -warnaserror+ -nologo -target:exe -out:"$work/FrameCost.exe" \
  -r:"$work/ParticlePhysics.dll" -r:"$facades" -r:System.Numerics.dll benchmarks/frame-cost/FrameCost.cs \
  || die "mcs could not compile FrameCost.cs"

csv=benchmarks/ParticlePhysics.Benchmarks/stable-time-steps.csv
started=$(date -u '+%Y-%m-%d %H:%M UTC')
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
echo "-- .NET ($rounds rounds)" >&2
dotnet "$clr/FrameCost.dll" --steps-from "$csv" --n "$n" --rounds "$rounds" >"$work/clr.txt" || { cat "$work/clr.txt"; die "the program failed on .NET"; }
echo "-- Mono ($rounds rounds)" >&2
mono "$work/FrameCost.exe" --steps-from "$csv" --n "$n" --rounds "$rounds" >"$work/mono.txt" || { cat "$work/mono.txt"; die "the program failed on Mono"; }
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

grep '^hash ' "$work/clr.txt" >"$work/clr.hash"
grep '^hash ' "$work/mono.txt" >"$work/mono.hash"
diff "$work/clr.hash" "$work/mono.hash" >&2 || die "Mono (>) and .NET (<) computed different bits"

echo "$started; $(benchmarks/machine.sh); load average $load_before before, $load_after after;"
echo "$(sed -n 's/^runtime //p' "$work/clr.txt") and $(sed -n 's/^runtime //p' "$work/mono.txt" | cut -d' ' -f1-2);" \
  "\`benchmarks/frame-cost/run.sh --rounds $rounds --n $n\`. The same bits on both runtimes and on one thread and two."
echo
awk -v n="$n" '
  function name(label,   base, tol) {
    base = label; tol = ""
    if (index(label, "@") > 0) { base = substr(label, 1, index(label, "@") - 1); tol = substr(label, index(label, "@") + 1) }
    if (base == "explicit-euler") return "explicit Euler"
    if (base == "semi-implicit-euler") return "semi-implicit Euler"
    if (base == "implicit-euler") return sprintf("implicit Euler, tolerance %s (%s CG it./frame)", tol, iterations[label])
    if (base == "rk4") return "RK4"
    if (base == "velocity-verlet") return "velocity Verlet"
    if (base == "rk45") return "RK45 (adaptive, tolerance 1e-8)"
    if (base == "xpbd") return "xpbd (10 substeps)"
    return base
  }
  FNR == NR && $1 == "count" { iterations[$2] = $4 }
  $1 == "frame" {
    side = (FNR == NR) ? "clr" : "mono"
    cell[side, $2, $3] = sprintf("%.2f (%.2f)", $4, $5)
    if ($3 == 1) cpu[side, $2] = ($8 < 0) ? "-" : sprintf("%.2f", $8)
    if (!($2 in seen)) { seen[$2] = 1; order[++count] = $2; steps[$2] = $6; dt[$2] = $7 }
  }
  END {
    printf "| integrator (%d x %d cloth) | steps per frame (dt) | .NET, 1 thread | .NET, 2 threads | Mono, 1 thread | Mono, 2 threads | 1 thread, CPU: .NET / Mono |\n", n, n
    print "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
    for (i = 1; i <= count; i++) {
      c = order[i]
      s = (c == "rk45") ? "1 call (adaptive)" : sprintf("%d (%.3f ms)", steps[c], dt[c] * 1000)
      printf "| %s | %s | %s | %s | %s | %s | %s / %s |\n", name(c), s, cell["clr", c, 1], cell["clr", c, 2], cell["mono", c, 1], cell["mono", c, 2], cpu["clr", c], cpu["mono", c]
    }
  }' "$work/clr.txt" "$work/mono.txt"
echo
echo "Milliseconds per 60 Hz frame (1/60 s of simulated time), each round one simulated second from rest: wall time, the"
echo "fastest of $rounds rounds (the median in brackets); last column, the one-thread runs' fastest in the CPU time of the"
echo "timing thread, which leaves out waiting for a core on a loaded machine. At 60 fps a frame has 16.7 ms for everything."
