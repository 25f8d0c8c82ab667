#!/usr/bin/env bash
# Set up (idempotent) and run the whole test suite: the README's test command.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m pip install --quiet --disable-pip-version-check -e '.[test]'
python3 -m ruff check src tests benchmarks
python3 -m pytest "$@"
