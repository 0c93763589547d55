#!/usr/bin/env bash
# Set up a fresh Debian/Ubuntu machine for Kezuri CAM. Safe to run again.
#
#   scripts/setup.sh --demo   a Python 3.11 venv (.venv) with the pinned runtime packages
#                             (requirements.txt): what ./demo.sh and batch.py need
#   scripts/setup.sh --test   the same, plus the test-only packages (requirements-test.txt) and
#                             LinuxCNC's rs274 G-code interpreter (the tests check every program
#                             we write with it): what ./test.sh needs
#
# PYTHON=/path/to/python3.11 picks the interpreter (default: python3.11 on the PATH).
set -euo pipefail
cd "$(dirname "$0")/.."

MODE=${1:---test}
case "$MODE" in
  --demo) REQUIREMENTS=requirements.txt ;;
  --test) REQUIREMENTS=requirements-test.txt ;;
  *) echo "usage: scripts/setup.sh --demo | --test (got '$MODE')" >&2; exit 2 ;;
esac

# The bpy 5.0.1 wheel exists for CPython 3.11 only: no other interpreter will do.
need_python() {
  cat >&2 <<MSG
Kezuri CAM needs Python 3.11: the bpy 5.0.1 wheel (Blender as a Python module) is built for
CPython 3.11 only. $1
Install it, then run this again:
  Debian 12 / Ubuntu 22.04:  sudo apt-get install python3.11 python3.11-venv
  Ubuntu 24.04:              sudo add-apt-repository ppa:deadsnakes/ppa && sudo apt-get install python3.11 python3.11-venv
  any Linux:                 uv python install 3.11 (or pyenv install 3.11), then PYTHON=/path/to/python3.11 $0 $MODE
MSG
  exit 1
}
PYTHON=${PYTHON:-python3.11}
command -v "$PYTHON" >/dev/null 2>&1 || need_python "'$PYTHON' is not on the PATH."
VERSION=$("$PYTHON" -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null || echo "?")
[ "$VERSION" = "3.11" ] || need_python "'$PYTHON' is Python $VERSION."
if [ -x .venv/bin/python ]; then
  VENV_VERSION=$(.venv/bin/python -c 'import sys; print("%d.%d" % sys.version_info[:2])' 2>/dev/null || echo "?")
  [ "$VENV_VERSION" = "3.11" ] || need_python ".venv was made with Python $VENV_VERSION: remove it (rm -rf .venv)."
fi
if ! "$PYTHON" -c 'import ensurepip, venv' >/dev/null 2>&1; then
  need_python "'$PYTHON' has no venv module (Debian/Ubuntu: the python3.11-venv package)."
fi

if [ "$MODE" = --test ] && ! command -v rs274 >/dev/null 2>&1; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends linuxcnc-uspace
fi

if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
# Each requirements file is installed again only when it changed (a copy is kept in .venv).
if ! cmp -s requirements.txt .venv/.requirements-installed; then
  .venv/bin/python -m pip install -q --upgrade pip
  .venv/bin/python -m pip install -q -r requirements.txt
  cp requirements.txt .venv/.requirements-installed
  rm -f .venv/.requirements-test-installed
fi
if [ "$MODE" = --test ] && ! cmp -s requirements-test.txt .venv/.requirements-test-installed; then
  .venv/bin/python -m pip install -q -r requirements-test.txt
  cp requirements-test.txt .venv/.requirements-test-installed
fi
