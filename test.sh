#!/usr/bin/env bash
# Runs every test: sets up what is missing (idempotent), the static gates (ruff, mypy), then pytest.
# Extra arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")"
./setup.sh --no-run
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
# Static gates first (configured in pyproject.toml); a finding fails the build before any test runs.
echo "== ruff"; .venv/bin/ruff check .
echo "== mypy"; .venv/bin/mypy
exec .venv/bin/python -m pytest "$@"
