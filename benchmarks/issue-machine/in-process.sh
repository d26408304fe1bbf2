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
side() { # side NAME COMMIT-or-empty: builds the shim against that library into $work/NAME-bin
  local name=$1 commit=$2 lib
  if [ -n "$commit" ]; then
    mkdir -p "$work/$name-src"
    git -C "$root" archive "$commit" src Directory.Build.props Directory.Packages.props global.json nuget.config .editorconfig \
      | tar -x -C "$work/$name-src"
    lib="$work/$name-src/src/ParticlePhysics/ParticlePhysics.csproj"
  else
    lib="$root/src/ParticlePhysics/ParticlePhysics.csproj"
  fi
  mkdir -p "$work/$name"
  cp "$here/in-process/Shim.cs" "$work/$name/"
  cat > "$work/$name/Shim.csproj" <<PROJ
<Project Sdk="Microsoft.NET.Sdk">
  <PropertyGroup>
    <TargetFramework>net10.0</TargetFramework>
    <Nullable>enable</Nullable>
    <NuGetAudit>false</NuGetAudit>
  </PropertyGroup>
  <ItemGroup>
    <ProjectReference Include="$lib" />
  </ItemGroup>
</Project>
PROJ
  dotnet build -c Release -v q -nologo "$work/$name" -o "$work/$name-bin" > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; exit 1; }
}
side a "$A"
side b "$B"
mkdir -p "$work/host"
cp "$here/in-process/Host.cs" "$work/host/"
cat > "$work/host/Host.csproj" <<'PROJ'
<Project Sdk="Microsoft.NET.Sdk">
  <PropertyGroup>
    <OutputType>Exe</OutputType>
    <TargetFramework>net10.0</TargetFramework>
    <Nullable>enable</Nullable>
    <NuGetAudit>false</NuGetAudit>
  </PropertyGroup>
</Project>
PROJ
dotnet build -c Release -v q -nologo "$work/host" -o "$work/host-bin" > "$work/host.log" 2>&1 || { cat "$work/host.log"; exit 1; }
echo "A: ${A}, B: ${B:-the working tree}; $rounds rounds of one simulated second each, $n x $n cloth; load $(cut -d' ' -f1-3 /proc/loadavg)"
dotnet "$work/host-bin/Host.dll" "$work/a-bin" "$work/b-bin" "$rounds" "$tolerance_a" "$tolerance_b" "$n" | tee "$work/out.txt"
median=$(sed -n 's/.*median \([0-9.]*\),.*/\1/p' "$work/out.txt" | tail -1)
if [ "$A" = "460bc80^" ] && [ "$tolerance_a" = 1e-3 ] && [ "$tolerance_b" = 1e-3 ] && [ "$n" = 64 ]; then
  python3 -c "print(f'on the issue\'s machine (0.19 s there for A): B about {0.19 * $median:.3f} s per simulated second')"
fi
