#!/usr/bin/env bash
# Set up a fresh Debian/Ubuntu machine for Kezuri CAM: LinuxCNC's rs274 interpreter (to check
# the G-code we write) and a Python 3.11 venv with the pinned packages. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v rs274 >/dev/null 2>&1; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends linuxcnc-uspace
fi

PYTHON="${PYTHON:-python3.11}"
command -v "$PYTHON" >/dev/null 2>&1 || PYTHON=python3
if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
if ! cmp -s requirements.txt .venv/.requirements-installed 2>/dev/null; then
  .venv/bin/python -m pip install -q --upgrade pip
  .venv/bin/python -m pip install -q -r requirements.txt
  cp requirements.txt .venv/.requirements-installed
fi
