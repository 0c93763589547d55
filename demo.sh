#!/usr/bin/env bash
# Set up what the demo needs (scripts/setup.sh --demo) and run it: every workflow on its built-in
# sample part, NC programs, report.json and preview pictures into ./demo-out (or $1).
set -euo pipefail
cd "$(dirname "$0")"
./scripts/setup.sh --demo
exec .venv/bin/python batch.py demo --out "${1:-demo-out}"
