# Sourced by run.sh and in-process.sh (which set root and work): the library a side runs and the small programs
# built against it, in a temporary folder.

# library_project NAME COMMIT: prints the library project to build against: the working tree's when COMMIT is
# empty, else that commit's, archived from git into $work/NAME-src.
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

# build_program NAME KIND LIBRARY SOURCE [ASSEMBLY]: the project $work/NAME/NAME.csproj (KIND Exe or Library; its
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
