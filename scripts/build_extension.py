"""Build the installable extension zips, one per platform, into dist/.

    .venv/bin/python scripts/build_extension.py [--platforms linux-x64,...] [--out dist]

Downloads the wheels Blender lacks (manifold3d, trimesh, numba with llvmlite, and embreex where a
wheel exists) for every platform and for both Pythons Blender 4.2-5.x ships (cp311, cp313),
stages a copy of the extension with those wheels listed in its manifest, and runs Blender's own
extension tool (shipped in the bpy wheel) with --split-platforms.  numpy is not bundled: Blender has it.
Wheels are fetched by this build, never committed.
"""
from __future__ import annotations

import argparse
import glob
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PYTHONS = ("311", "313")
PLATFORMS = {  # Blender platform name -> the pip platform tags its wheels may carry
    "linux-x64": ("manylinux_2_28_x86_64", "manylinux_2_17_x86_64", "manylinux2014_x86_64"),
    "windows-x64": ("win_amd64",),
    "macos-arm64": ("macosx_11_0_arm64",),
    "macos-x64": ("macosx_10_15_x86_64", "macosx_10_14_x86_64"),
}
REQUIRED = ("manifold3d==3.5.4", "trimesh==5.2.0",
            "numba==0.61.2", "llvmlite==0.44.0")     # numba: the compiled height-field kernel
OPTIONAL = ("embreex==4.4.0.post1",          # faster ray casting for trimesh, not on every platform
            "pyvoronoi==1.2.8")             # V-carving's medial axis; no wheel for Intel macs (1.2.8)
MISSING = {"embreex": "trimesh falls back to numpy rays", "pyvoronoi": "V-carving says it cannot run there"}
STAGE_EXCLUDE = {".git", ".venv", "venv", "dist", "build", "tests", "bench", "docs", "scripts", ".ci",
                 "__pycache__", ".pytest_cache", "demo-out"}


def blender_ext() -> str:
    """Blender's extension command-line tool, shipped inside the bpy wheel."""
    import site
    path = [p for folder in site.getsitepackages() for p in
            glob.glob(os.path.join(folder, "bpy", "*", "scripts", "addons_core", "bl_pkg", "cli", "blender_ext.py"))]
    if not path:
        raise SystemExit("blender_ext.py not found in the bpy wheel")
    return path[0]


def download(requirement: str, platform_tags: tuple, python: str, folder: str, optional: bool) -> bool:
    tags = [word for tag in platform_tags for word in ("--platform", tag)]
    command = [sys.executable, "-m", "pip", "download", "-q", "--no-deps", "--only-binary=:all:",
               *tags, "--python-version", python, "--implementation", "cp",
               "--dest", folder, requirement]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode and not optional:
        raise SystemExit(f"cannot download {requirement} for {platform_tags[0]} cp{python}:\n{done.stderr}")
    return done.returncode == 0


def stage(folder: str, wheels: list, platforms: list):
    shutil.rmtree(folder, ignore_errors=True)
    shutil.copytree(ROOT, folder, ignore=lambda d, names: [n for n in names if n in STAGE_EXCLUDE
                                                           or n.endswith((".pyc", ".zip", ".whl"))])
    os.makedirs(os.path.join(folder, "wheels"))
    for wheel in wheels:
        shutil.copy(wheel, os.path.join(folder, "wheels"))
    manifest_path = os.path.join(folder, "blender_manifest.toml")
    manifest = open(manifest_path).read()
    listed = ",\n".join(f'  "./wheels/{os.path.basename(w)}"' for w in sorted(wheels))
    manifest = manifest.replace('blender_version_min = "4.2.0"',
                                'blender_version_min = "4.2.0"\n\n'
                                f"platforms = [{', '.join(repr(p).replace(chr(39), chr(34)) for p in platforms)}]\n\n"
                                f"wheels = [\n{listed}\n]")
    open(manifest_path, "w").write(manifest)


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--platforms", default=",".join(PLATFORMS))
    parser.add_argument("--out", default=os.path.join(ROOT, "dist"))
    args = parser.parse_args()
    platforms = [p for p in args.platforms.split(",") if p]
    for p in platforms:
        if p not in PLATFORMS:
            raise SystemExit(f"unknown platform {p!r}; choose from {', '.join(PLATFORMS)}")
    cache = os.path.join(ROOT, "build", "wheels")
    os.makedirs(cache, exist_ok=True)
    for p in platforms:
        for python in PYTHONS:
            for requirement in REQUIRED:
                download(requirement, PLATFORMS[p], python, cache, optional=False)
            for requirement in OPTIONAL:
                if not download(requirement, PLATFORMS[p], python, cache, optional=True):
                    print(f"note: no {requirement} wheel for {p} cp{python}; "
                          f"{MISSING[requirement.split('==')[0]]}")
    wheels = sorted(glob.glob(os.path.join(cache, "*.whl")))
    source = os.path.join(ROOT, "build", "stage", "kezuri")
    stage(source, wheels, platforms)
    os.makedirs(args.out, exist_ok=True)
    tool = blender_ext()
    subprocess.run([sys.executable, tool, "validate", source], check=True)
    subprocess.run([sys.executable, tool, "build", "--source-dir", source, "--output-dir", args.out,
                    "--split-platforms"], check=True)
    for path in sorted(glob.glob(os.path.join(args.out, "kezuri-*.zip"))):
        print(f"built {path} ({os.path.getsize(path) / 1e6:.1f} MB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
