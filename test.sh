#!/usr/bin/env bash
# Set up what the tests need (scripts/setup.sh --test: the demo's packages, the test-only ones and
# LinuxCNC's rs274) and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")"
./scripts/setup.sh --test
exec .venv/bin/python -m pytest -q tests "$@"
