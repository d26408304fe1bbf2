#!/usr/bin/env python3
"""Lay out ParticlePhysics as a Unity package (UPM) folder around the precompiled netstandard2.1 DLL.

    python3 tools/make-unity-package.py                    # builds Release, writes artifacts/unity/com.particlephysics.core
    python3 tools/make-unity-package.py --dll path/to/ParticlePhysics.dll --out DIR   # ParticlePhysics.Scenes.dll beside it

The folder holds package.json, README.md (the package users' README, src/ParticlePhysics/README.md), LICENSE.md,
CHANGELOG.md, Documentation~/unity.md, Runtime/ with the two DLLs (the core, and ParticlePhysics.Scenes, which loads
scene files and OBJ meshes) and their XML docs, and Samples~/Cloth with the sample
MonoBehaviour (samples/unity/Cloth, listed under "samples" in package.json: Package Manager offers to import it), and a
.meta file beside every asset and folder, as Unity requires in an immutable (git or registry) package. Each .meta's GUID is the MD5 of the package name and the asset's path, so it stays the same from run to
run and from version to version: Unity keeps the references of scenes and prefabs to the plugin across upgrades.
No .asmdef: Unity references a precompiled plugin DLL from every script assembly by itself (its PluginImporter
meta says "Any platform"). Standard library only, so that it runs wherever the .NET SDK does.
"""

import argparse
import hashlib
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

PACKAGE_NAME = "com.particlephysics.core"
DISPLAY_NAME = "ParticlePhysics"
UNITY_VERSION = "2021.3"
ROOT = Path(__file__).resolve().parent.parent
PROJECT = ROOT / "src" / "ParticlePhysics" / "ParticlePhysics.csproj"
SCENES_PROJECT = ROOT / "src" / "ParticlePhysics.Scenes" / "ParticlePhysics.Scenes.csproj"
PACKAGE_README = ROOT / "src" / "ParticlePhysics" / "README.md"
SAMPLES = [
    # (folder under Samples~, source folder, display name, description)
    ("Cloth", ROOT / "samples" / "unity" / "Cloth", "Simulated cloth",
     "A MonoBehaviour that hangs a cloth from two corners, steps it at 60 Hz with implicit Euler out of Update and "
     "draws it through a MeshFilter, interpolated, without allocating per frame; save and restore included."),
    ("MeshCloth", ROOT / "samples" / "unity" / "MeshCloth", "Mesh cloth",
     "A MonoBehaviour that turns the MeshFilter's mesh into a cloth of physical membrane and bending: welds its UV "
     "seams, pins the vertices painted red (or listed), attaches them to a transform, and writes positions and normals "
     "back each frame without allocating."),
]

DESCRIPTION = (
    "A particle (point mass) physics engine in double precision: a state-vector particle system, force generators "
    "(gravity, drag, spring networks), Euler, Verlet and Runge-Kutta integrators, cloth with render meshes, a fixed-timestep "
    "driver and save-game snapshots. Steps without allocating."
)

FOLDER_META = """fileFormatVersion: 2
guid: {guid}
folderAsset: yes
DefaultImporter:
  externalObjects: {{}}
  userData:
  assetBundleName:
  assetBundleVariant:
"""

TEXT_META = """fileFormatVersion: 2
guid: {guid}
TextScriptImporter:
  externalObjects: {{}}
  userData:
  assetBundleName:
  assetBundleVariant:
"""

# A C# script. Samples~ is not imported in place, but Package Manager copies a sample with its .meta files into
# Assets/Samples/, so a fixed GUID keeps the scenes that use the script working across versions.
SCRIPT_META = """fileFormatVersion: 2
guid: {guid}
MonoImporter:
  externalObjects: {{}}
  serializedVersion: 2
  defaultReferences: []
  executionOrder: 0
  icon: {{instanceID: 0}}
  userData:
  assetBundleName:
  assetBundleVariant:
"""

MANIFEST_META = """fileFormatVersion: 2
guid: {guid}
PackageManifestImporter:
  externalObjects: {{}}
  userData:
  assetBundleName:
  assetBundleVariant:
"""

# A managed plugin for every platform, editor included; validateReferences makes Unity check that everything it
# references (netstandard only) resolves.
PLUGIN_META = """fileFormatVersion: 2
guid: {guid}
PluginImporter:
  externalObjects: {{}}
  serializedVersion: 2
  iconMap: {{}}
  executionOrder: {{}}
  defineConstraints: []
  isPreloaded: 0
  isOverridable: 0
  isExplicitlyReferenced: 0
  validateReferences: 1
  platformData:
  - first:
      Any:
    second:
      enabled: 1
      settings: {{}}
  - first:
      Editor: Editor
    second:
      enabled: 0
      settings:
        DefaultValueInitialized: true
  userData:
  assetBundleName:
  assetBundleVariant:
"""


def guid(asset_path: str) -> str:
    """A stable Unity GUID (32 hex digits) for an asset path relative to the package root."""
    return hashlib.md5(f"{PACKAGE_NAME}/{asset_path}".encode("utf-8")).hexdigest()


def project_version() -> str:
    match = re.search(r"<Version>([^<]+)</Version>", PROJECT.read_text(encoding="utf-8"))
    if not match:
        sys.exit(f"error: no <Version> in {PROJECT}")
    return match.group(1).strip()


def build_dll(configuration: str) -> Path:
    output = ROOT / "artifacts" / "unity-build"
    subprocess.run(
        ["dotnet", "build", str(SCENES_PROJECT), "-c", configuration, "-o", str(output), "--nologo", "-v", "quiet"],
        check=True,
    )
    return output / "ParticlePhysics.dll"


def write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dll", type=Path, help="a built ParticlePhysics.dll, with ParticlePhysics.Scenes.dll beside it "
                        "(default: build src/ParticlePhysics.Scenes, which builds the core)")
    parser.add_argument("--out", type=Path, default=ROOT / "artifacts" / "unity",
                        help="the folder to create the package folder in (default: artifacts/unity)")
    parser.add_argument("--version", help="the package version (default: <Version> of the csproj)")
    parser.add_argument("--configuration", default="Release", help="the build configuration (default: Release)")
    args = parser.parse_args()

    dll = args.dll.resolve() if args.dll else build_dll(args.configuration)
    xml = dll.with_suffix(".xml")
    scenes = dll.with_name("ParticlePhysics.Scenes.dll")
    scenes_xml = scenes.with_suffix(".xml")
    for required in (dll, xml, scenes, scenes_xml):
        if not required.is_file():
            sys.exit(f"error: {required} does not exist (build the core first, or omit --dll)")
    version = args.version or project_version()
    if not re.fullmatch(r"\d+\.\d+\.\d+(-[0-9A-Za-z.-]+)?", version):
        sys.exit(f"error: version {version!r} is not a semantic version such as 1.2.3, as Unity requires")

    package = args.out.resolve() / PACKAGE_NAME
    if package.exists():
        shutil.rmtree(package)
    package.mkdir(parents=True)

    manifest = {
        "name": PACKAGE_NAME,
        "version": version,
        "displayName": DISPLAY_NAME,
        "description": DESCRIPTION,
        "unity": UNITY_VERSION,
        "license": "MIT",
        "keywords": ["physics", "particles", "cloth", "mass-spring", "integrator"],
        "author": {"name": "The ParticlePhysics contributors"},
        "samples": [
            {"displayName": display, "description": description, "path": f"Samples~/{folder}"}
            for folder, _, display, description in SAMPLES
        ],
    }
    write(package / "package.json", json.dumps(manifest, indent=2) + "\n")
    write(package / "package.json.meta", MANIFEST_META.format(guid=guid("package.json")))

    for source, name in ((PACKAGE_README, "README.md"), (ROOT / "LICENSE", "LICENSE.md"), (ROOT / "CHANGELOG.md", "CHANGELOG.md")):
        shutil.copyfile(source, package / name)
        write(package / f"{name}.meta", TEXT_META.format(guid=guid(name)))

    # Folders whose names end in ~ are ignored by Unity's importer: no .meta there.
    (package / "Documentation~").mkdir()
    shutil.copyfile(ROOT / "docs" / "unity.md", package / "Documentation~" / "unity.md")

    runtime = package / "Runtime"
    runtime.mkdir()
    write(package / "Runtime.meta", FOLDER_META.format(guid=guid("Runtime")))
    for assembly, docs in ((dll, xml), (scenes, scenes_xml)):
        shutil.copyfile(assembly, runtime / assembly.name)
        write(runtime / f"{assembly.name}.meta", PLUGIN_META.format(guid=guid(f"Runtime/{assembly.name}")))
        shutil.copyfile(docs, runtime / docs.name)
        write(runtime / f"{docs.name}.meta", TEXT_META.format(guid=guid(f"Runtime/{docs.name}")))

    for folder, source, _, _ in SAMPLES:
        for script in sorted(source.glob("*.cs")):
            asset = f"Samples~/{folder}/{script.name}"
            (package / asset).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(script, package / asset)
            write(package / f"{asset}.meta", SCRIPT_META.format(guid=guid(asset)))

    print(package)
    return 0


if __name__ == "__main__":
    sys.exit(main())
