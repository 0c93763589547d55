"""The extension as users get it: built into a zip with its wheels, installed by Blender."""
import glob
import json
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture(scope="module")
def linux_zip(tmp_path_factory):
    out = tmp_path_factory.mktemp("dist")
    subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "build_extension.py"), "--platforms", "linux-x64",
                    "--out", str(out)], check=True, capture_output=True, timeout=900)
    zips = glob.glob(str(out / "kezuri-*-linux_x64.zip"))
    assert len(zips) == 1
    return zips[0]


def test_manifest_passes_blenders_validator():
    import site
    tool = [p for folder in site.getsitepackages() for p in
            glob.glob(os.path.join(folder, "bpy", "*", "scripts", "addons_core", "bl_pkg", "cli", "blender_ext.py"))]
    done = subprocess.run([sys.executable, tool[0], "validate", ROOT], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr


def test_installed_zip_runs_on_its_bundled_wheels_and_disables_cleanly(linux_zip, tmp_path):
    env = dict(os.environ, BLENDER_USER_RESOURCES=str(tmp_path / "user"))
    env.pop("KEZURI_TOOL_LIBRARY", None)                # the library is the one in the user config folder
    done = subprocess.run([sys.executable, os.path.join(ROOT, "tests", "install_check.py"), linux_zip],
                          capture_output=True, text=True, env=env, timeout=600)
    lines = [line for line in done.stdout.splitlines() if line.startswith("RESULT ")]
    assert done.returncode == 0 and lines, done.stdout[-2000:] + done.stderr[-3000:]
    result = json.loads(lines[0][len("RESULT "):])
    assert result["install"] == ["FINISHED"]
    assert result["manifold3d"].startswith(str(tmp_path / "user"))
    assert result["trimesh"].startswith(str(tmp_path / "user"))
    assert result["numba"].startswith(str(tmp_path / "user"))
    for operator in ("engrave_generate", "simulate", "rotary_generate", "import_stepnc", "stepnc_generate",
                     "turnmill_generate", "unfold_quad", "add_elbow"):
        assert result[operator] == ["FINISHED"], operator
    # The 10 x 10 x 5 stock minus a 2 mm flat slot, 6 mm long and 1 mm deep: (6 * 2 + pi) * 1 mm^3;
    # the faceted tool leaves a little material.
    assert result["process_job_volume"] == pytest.approx(500.0 - (12.0 + 3.14159), abs=0.15)   # 1 % of the cut
    assert result["registered"] is True
    assert result["engrave_generate"] == ["FINISHED"] and result["kezuri_objects"] >= 3
    assert result["move_old_tools"] == ["FINISHED"] and result["old_tools_after"] == 0
    assert result["library_path"].startswith(str(tmp_path / "user"))          # the user config folder
    assert result["moved_tool"] == ["ball", 8.0, "8 mm ball"]
    assert result["rough_from_library"] == [8.0, 17]
    assert "T7 12 mm 90° V-bit" in result["bad_library_tool"]
    assert "the engrave's rough tool must be a ball end mill" in result["bad_library_tool"]
    assert result["rough_after_bad"] == [8.0, 17]                                           # nothing taken
    assert result["scene_post"] == "grbl"      # "Preferences Default" resolves to the preferences' post
    assert result["registered_after_disable"] is False
