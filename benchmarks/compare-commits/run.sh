#!/usr/bin/env bash
# Is my change slower than commit A? Two libraries in one process, round by round: the library of commit A (default
# HEAD) and the working tree's (B), each with Shim.cs compiled against it and loaded into its own AssemblyLoadContext
# by Host.cs. The host alternates them every simulated second (and which goes first), so both sides see the same
# machine from one round to the next: on a shared, noisy host the per-round ratios B / A scatter far less than times
# taken in separate processes. It prints each side's fastest and median round, the median and quartiles of the
# per-round ratios, and whether both ended in the same bits. Needs git history, the .NET SDK and tar.
#   run.sh [rounds] [tolerance B] [tolerance A] [n]      defaults: 40 rounds, 1e-3, 1e-3, the 64 x 64 cloth
#   A=<commit> run.sh ...         another library for A (a commit, tag or branch)
#   B=<commit> run.sh ...         a commit for B instead of the working tree
#   RUNNER=2 run.sh ...           both sides step on a WorkerThreadRunner(2) of their own library
#   INTEGRATOR=<name> run.sh ...  another integrator of the catalog (default implicit-euler; the tolerances apply to
#                                 implicit Euler only); STEPS=<k>: steps per 60 Hz frame (default 1 for implicit-euler,
#                                 xpbd and rk45; for the others the fewest stable steps, from stable-time-steps.csv)
# The same commit on both sides with two tolerances measures the cost of one tolerance against the other.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
A=${A:-HEAD}
B=${B:-}
INTEGRATOR=${INTEGRATOR:-implicit-euler}
rounds=${1:-40}
tolerance_b=${2:-1e-3}
tolerance_a=${3:-1e-3}
n=${4:-64}
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# Steps per 1/60 s frame: one for the integrators that take a frame in one step, else ceil((1/60) / largest stable dt).
if [ -z "${STEPS:-}" ]; then
  case "$INTEGRATOR" in
    implicit-euler | xpbd | rk45) STEPS=1 ;;
    *)
      STEPS=$(awk -F, -v name="$INTEGRATOR" -v n="$n" '$1 == name && $2 == n { s = (1 / 60) / $3; k = int(s); if (k < s) k++; print k }' \
        "$root/benchmarks/ParticlePhysics.Benchmarks/stable-time-steps.csv")
      [ -n "$STEPS" ] || { echo "compare-commits: no stable dt for $INTEGRATOR at n = $n in stable-time-steps.csv: set STEPS" >&2; exit 2; }
      ;;
  esac
fi

# library_project NAME COMMIT: the library project a side builds against: the working tree's when COMMIT is empty,
# else that commit's, archived from git into $work/NAME-src.
library_project() {
  local name=$1 commit=$2
  if [ -z "$commit" ]; then
    echo "$root/src/ParticlePhysics/ParticlePhysics.csproj"
    return
  fi
  mkdir -p "$work/$name-src"
  git -C "$root" archive "$commit" src Directory.Build.props Directory.Packages.props global.json nuget.config .editorconfig \
    | tar -x -C "$work/$name-src"
  echo "$work/$name-src/src/ParticlePhysics/ParticlePhysics.csproj"
}

# build_program NAME KIND LIBRARY SOURCE [ASSEMBLY]: the project $work/NAME/NAME.csproj (KIND Exe or Library, its
# assembly ASSEMBLY, NAME by default) with SOURCE copied in and a reference to LIBRARY when it is not empty, built
# (Release) into $work/NAME-bin; its log on failure.
build_program() {
  local name=$1 kind=$2 library=$3 source=$4 assembly=${5:-$1} reference=""
  [ -n "$library" ] && reference="<ItemGroup><ProjectReference Include=\"$library\" /></ItemGroup>"
  mkdir -p "$work/$name"
  cp "$source" "$work/$name/"
  cat > "$work/$name/$name.csproj" <<PROJ
<Project Sdk="Microsoft.NET.Sdk">
  <PropertyGroup>
    <OutputType>$kind</OutputType>
    <AssemblyName>$assembly</AssemblyName>
    <TargetFramework>net10.0</TargetFramework>
    <Nullable>enable</Nullable>
    <NuGetAudit>false</NuGetAudit>
  </PropertyGroup>
  $reference
</Project>
PROJ
  dotnet build -c Release -v q -nologo "$work/$name" -o "$work/$name-bin" > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; exit 1; }
}

# Each side's shim is the assembly Shim, which Host.cs loads from the side's folder.
build_program a Library "$(library_project a "$A")" "$here/Shim.cs" Shim
build_program b Library "$(library_project b "$B")" "$here/Shim.cs" Shim
build_program Host Exe "" "$here/Host.cs"
echo "A: $A ($(git -C "$root" rev-parse --short "$A")), B: ${B:-the working tree}; $INTEGRATOR, $STEPS step(s) per 1/60 s frame, $n x $n cloth, RUNNER=${RUNNER:-1}"
echo "$rounds rounds of one simulated second each, alternating; load $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
dotnet "$work/Host-bin/Host.dll" "$work/a-bin" "$work/b-bin" "$rounds" "$tolerance_a" "$tolerance_b" "$n" "$INTEGRATOR" "$STEPS"
