#!/usr/bin/env bash
# Set up (idempotent) and run the whole test suite: the README's test command.
# bash scripts/test.sh --fast leaves out the slow tests; other arguments go to pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
# the project's own virtual environment .venv, made if missing (scripts/setup.sh)
python="$(bash scripts/setup.sh test | tail -n 1)"
# the browser tests drive Debian's chromium through playwright (never `playwright install`)
if [ ! -x /usr/bin/chromium ]; then
    if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq chromium >/dev/null
fi
# CalculiX runs the FE tests and the exported INP deck; the Khronos glTF validator checks
# the GLB (project-local, not committed)
if ! command -v ccx >/dev/null; then
    if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq calculix-ccx
fi
if [ ! -d .cache/npm/node_modules/gltf-validator ]; then
    if ! command -v npm >/dev/null; then
        if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
        $sudo apt-get update -qq
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq npm >/dev/null
    fi
    npm install --silent --prefix .cache/npm gltf-validator
fi
"$python" -m ruff check src tests benchmarks examples
"$python" -m mypy
# --fast: leave out the tests marked slow (under a minute on two cores); CI runs everything
if [ "${1:-}" = "--fast" ]; then
    shift
    set -- -m "not slow" "$@"
fi
# two pytest-xdist workers; the tests sharing a module fixture run on one of them
# (tests/conftest.py); -n 0 after the script's arguments runs everything in one process
"$python" -m pytest -n 2 --dist loadgroup "$@"
