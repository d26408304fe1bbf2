#!/usr/bin/env bash
# Runs every benchmark whose table docs/benchmarks.md shows, in one go, and prints the page's tables: the frame cost
# of every integrator on .NET and Mono (frame-cost/run.sh), RK4 against the C reference, Math.NET and the student
# baseline, RK4 and xpbd on two threads, xpbd against its C reference, implicit Euler per simulated second, quality,
# the contact stage, OBJ parsing and the demo's share of time in the steps; then the targets with met / not met.
# Each table carries its date, machine, load average and command. results.py turns the programs' outputs into the
# tables; with --write it also puts them into docs/benchmarks.md between its "results.sh" markers, so refreshing the
# page is this one command. About 15 minutes on a quiet 2-core machine, 25 on a loaded one.
# Needs the .NET SDK, mono-devel (mono, mcs), gcc, python3; perf for the demo's share (skipped without it).
#   results.sh [--write] [--quick] [--keep]
#     --quick: small cloths and one round, to check the script (not measurements)
#     --keep: keep the programs' outputs (the folder is printed); results.py FOLDER [--write PAGE] formats them again
set -euo pipefail
cd "$(dirname "$0")/.."
export DOTNET_CLI_TELEMETRY_OPTOUT=1 DOTNET_NOLOGO=1 DOTNET_SKIP_FIRST_TIME_EXPERIENCE=1
die() { echo "results: $*" >&2; exit 1; }

write=""
quick=""
keep=""
while [ $# -gt 0 ]; do
  case "$1" in
    --write) write=docs/benchmarks.md; shift ;;
    --quick) quick=1; shift ;;
    --keep) keep=1; shift ;;
    *) die "unknown argument $1 (usage: results.sh [--write] [--quick] [--keep])" ;;
  esac
done

work=$(mktemp -d /tmp/pp-results.XXXXXX)
if [ -n "$keep" ]; then echo "results: the outputs stay in $work" >&2; else trap 'rm -rf "$work"' EXIT; fi
bench=benchmarks/ParticlePhysics.Benchmarks
P="dotnet run -c Release --project $bench --"               # as the page shows the commands
run_p() { dotnet "$bench/bin/Release/net10.0/ParticlePhysics.Benchmarks.dll" "$@"; } # what they run, built once

# step NAME SHOWN COMMAND...: runs COMMAND, its output in $work/NAME.out; $work/NAME.meta keeps the start, the load
# average before and after, and SHOWN, the command as the page prints it.
step() {
  local name=$1 shown=$2
  shift 2
  echo "-- $name: $shown" >&2
  {
    echo "started $(date -u '+%Y-%m-%d %H:%M UTC')"
    echo "load_before $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "command $shown"
  } >"$work/$name.meta"
  "$@" >"$work/$name.out" 2>"$work/$name.err" || { tail -30 "$work/$name.out" "$work/$name.err" >&2; die "$name failed"; }
  echo "load_after $(cut -d' ' -f1-3 /proc/loadavg)" >>"$work/$name.meta"
}

if [ -n "$quick" ]; then
  frame_args="--rounds 1 --n 16"; bdn_args="--job Dry"; c_sizes="16 32"; xpbd_sizes=16; cores_sizes=48; rounds=1
  implicit_n=16; quality_n=16; contact_sizes=1000,2000,4000; obj_vertices=10000; export PARTICLEPHYSICS_BENCH_QUICK=1
else
  frame_args="--rounds 5 --n 64"; bdn_args="--launchCount 1 --warmupCount 3 --iterationCount 9"; c_sizes="16 32 64 128 256"
  xpbd_sizes=32,64,128,256; cores_sizes=64,128; rounds=7; implicit_n=64; quality_n=64; contact_sizes=1000,10000,100000
  obj_vertices=1000000
fi

echo "-- build" >&2
dotnet build "$bench" -c Release --nologo -v quiet >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; die "the build failed"; }
dotnet build samples/ParticlePhysics.Demo -c Release --nologo -v quiet >>"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; die "the demo's build failed"; }
benchmarks/reference-c/run.sh --build
{
  echo "machine $(benchmarks/machine.sh)"
  echo "dotnet $(dotnet --list-runtimes | awk '$1 == "Microsoft.NETCore.App" && $2 ~ /^10\./ { v = $2 } END { print v }')"
  echo "gcc $(gcc -dumpfullversion)"
  echo "quick ${quick:-0}"
} >"$work/machine"
started=$(date -u '+%Y-%m-%d %H:%M UTC')

# The comparisons are only worth timing if everything computes the same cloth and a step allocates nothing.
step verify "$P verify" run_p verify
# shellcheck disable=SC2086 # the argument lists are lists
step frame "benchmarks/frame-cost/run.sh $frame_args" benchmarks/frame-cost/run.sh $frame_args
# shellcheck disable=SC2086
step bdn "$P --filter '*ClothStepBenchmarks.Rk4Step*' '*ComparisonBenchmarks*' '*.ParallelBenchmarks.*' $bdn_args --inProcess" \
  run_p --filter '*ClothStepBenchmarks.Rk4Step*' '*ComparisonBenchmarks*' '*.ParallelBenchmarks.*' $bdn_args --inProcess \
  --exporters json --artifacts "$work/bdn"
# shellcheck disable=SC2086
step c-rk4 "benchmarks/reference-c/run.sh $c_sizes" benchmarks/reference-c/run.sh $c_sizes
step xpbd "$P xpbd --sizes $xpbd_sizes --rounds $rounds" run_p xpbd --sizes "$xpbd_sizes" --rounds "$rounds"
step xpbd-cores "$P xpbd --cores --sizes $cores_sizes --rounds $rounds" run_p xpbd --cores --sizes "$cores_sizes" --rounds "$rounds"
for tolerance in 1e-3 1e-6; do
  step "implicit-$tolerance" "$P runner --engine implicit-euler --n $implicit_n --tolerance $tolerance --rounds $((rounds + 4))" \
    run_p runner --engine implicit-euler --n "$implicit_n" --tolerance "$tolerance" --rounds $((rounds + 4))
done
step quality "$P quality --n $quality_n" run_p quality --n "$quality_n"
step contacts "$P contacts --sizes $contact_sizes --rounds 5" run_p contacts --sizes "$contact_sizes" --rounds 5
step obj "$P obj --vertices $obj_vertices --rounds 5" run_p obj --vertices "$obj_vertices" --rounds 5

# The demo's runs of issues 5 and 13 under perf: the share of the process's samples inside ParticleWorld.Step.
demo=samples/ParticlePhysics.Demo/bin/Release/net10.0/ParticlePhysics.Demo.dll
# profile NAME DEMO-ARGS...: the demo run under perf record; prints the share in the step, or nothing without perf.
profile() {
  local name=$1
  shift
  command -v perf >/dev/null || return 0
  DOTNET_PerfMapEnabled=3 DOTNET_EnableWriteXorExecute=0 perf record -q -F 999 -g -o "$work/$name.data" -- \
    dotnet "$demo" cloth --format csv "$@" >/dev/null 2>"$work/$name.perf.err" \
    || { echo "perf record failed: $(tail -1 "$work/$name.perf.err")" >&2; return 0; }
  local pid
  pid=$(perf script -i "$work/$name.data" -F pid 2>/dev/null | head -1 | tr -d ' ')
  perf report -i "$work/$name.data" --children --sort symbol --stdio -g none 2>/dev/null \
    | awk '/ParticlePhysics\.ParticleWorld::Step\(/ { sub("%", "", $1); share += $1 } END { printf "%.1f\n", share }'
  [ -n "$pid" ] && rm -f "/tmp/perf-$pid.map"
}
# Each line: the issue, the share in the step [%] (empty without perf), the demo's arguments.
demo_runs() {
  local rk4 xpbd
  if [ -z "$quick" ]; then
    rk4="--resolution 1/127 --dt 0.00025 --duration 0.2"
    xpbd="--integrator xpbd --substeps 10 --resolution 1/63 --dt 0.0166667 --duration 10"
  else
    rk4="--resolution 1/15 --dt 0.001 --duration 0.2"
    xpbd="--integrator xpbd --substeps 10 --resolution 1/15 --dt 0.0166667 --duration 1"
  fi
  # shellcheck disable=SC2086 # the argument lists are lists
  echo "5|$(profile demo-rk4 $rk4)|cloth $rk4"
  # shellcheck disable=SC2086
  echo "13|$(profile demo-xpbd $xpbd)|cloth $xpbd"
}
dotnet "$demo" cloth --resolution 1/15 --duration 0.01 >/dev/null || die "the demo does not run"
step demo "perf record -g dotnet $demo ..." demo_runs

echo "started $started" >>"$work/machine"
echo "ended $(date -u '+%Y-%m-%d %H:%M UTC')" >>"$work/machine"
python3 benchmarks/results.py "$work" ${write:+--write "$write"}
