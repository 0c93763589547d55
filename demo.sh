#!/usr/bin/env bash
# Set up everything (scripts/setup.sh) and run the demo: every workflow on its built-in
# sample part, NC programs, report.json and preview pictures into ./demo-out (or $1).
set -euo pipefail
cd "$(dirname "$0")"
./scripts/setup.sh
exec .venv/bin/python batch.py demo --out "${1:-demo-out}"
