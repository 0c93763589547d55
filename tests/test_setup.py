"""scripts/setup.sh on a machine without Python 3.11: a clear message saying what to install,
exit 1, and nothing made (no .venv, no apt-get).

Each case runs the script from a copy of the repository's set-up files in a temporary folder,
with a PATH of its own that holds the shell tools the script uses and no python3.11.
"""
import os
import shutil
import subprocess

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOOLS = ("bash", "env", "cat", "cmp", "cp", "rm", "dirname", "id", "grep", "printf", "sudo", "apt-get")


def sandbox(tmp_path, extra: dict | None = None):
    repo = tmp_path / "repo"
    (repo / "scripts").mkdir(parents=True)
    for name in ("requirements.txt", "requirements-test.txt"):
        shutil.copy(os.path.join(ROOT, name), repo / name)
    shutil.copy(os.path.join(ROOT, "scripts", "setup.sh"), repo / "scripts" / "setup.sh")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for tool in TOOLS:
        found = shutil.which(tool)
        if found:
            os.symlink(found, bin_dir / tool)
    for name, text in (extra or {}).items():
        path = bin_dir / name
        path.write_text(text)
        path.chmod(0o755)
    return repo, {"PATH": str(bin_dir), "HOME": str(tmp_path)}


def run(repo, env, *args):
    return subprocess.run(["bash", str(repo / "scripts" / "setup.sh"), *args], env=env, capture_output=True,
                          text=True, timeout=60, cwd=repo)


@pytest.mark.parametrize("mode", ["--demo", "--test"])
def test_no_python311_on_the_path(tmp_path, mode):
    repo, env = sandbox(tmp_path)
    assert shutil.which("python3.11", path=env["PATH"]) is None
    done = run(repo, env, mode)
    assert done.returncode == 1
    assert "needs Python 3.11" in done.stderr and "'python3.11' is not on the PATH" in done.stderr
    assert "apt-get install python3.11 python3.11-venv" in done.stderr
    assert not (repo / ".venv").exists()
    assert "apt-get update" not in done.stdout + done.stderr       # nothing installed before the check


def test_another_python_named_python311_is_refused(tmp_path):
    """An interpreter that is not 3.11 (here a script answering 3.13 for the version query)."""
    repo, env = sandbox(tmp_path, {"python3.11": "#!/bin/bash\necho 3.13\n"})
    done = run(repo, env, "--demo")
    assert done.returncode == 1
    assert "'python3.11' is Python 3.13" in done.stderr
    assert not (repo / ".venv").exists()


def test_unknown_mode_is_a_usage_error(tmp_path):
    repo, env = sandbox(tmp_path)
    done = run(repo, env, "--everything")
    assert done.returncode == 2
    assert "usage: scripts/setup.sh --demo | --test (got '--everything')" in done.stderr


def test_demo_requirements_hold_no_test_package():
    """The demo installs the runtime only; the test file adds to it (and pins every package)."""
    def names(path):
        with open(os.path.join(ROOT, path)) as stream:
            lines = [line.strip() for line in stream if line.strip() and not line.startswith("#")]
        return lines
    runtime, test = names("requirements.txt"), names("requirements-test.txt")
    assert test[0] == "-r requirements.txt"
    assert all("==" in line for line in runtime + test[1:])
    runtime_names = {line.split("==")[0].lower() for line in runtime}
    assert {"bpy", "numpy", "manifold3d", "trimesh", "numba"} <= runtime_names
    assert not runtime_names & {"pytest", "hypothesis", "ezdxf", "sortedcontainers"}
