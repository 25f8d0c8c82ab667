#!/usr/bin/env bash
# Make the project's virtual environment .venv if it is missing and install the project into
# it with the extra given (default: all). Works where the system python3 refuses pip
# (PEP 668, Debian and Ubuntu) and where python3 is already a venv or pyenv.
# Prints the path of the environment's python on its last line.
set -euo pipefail
cd "$(dirname "$0")/.."
extra="${1:-all}"
as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
if [ ! -x .venv/bin/python ]; then
    if ! python3 -m venv .venv >/dev/null 2>&1; then
        # Debian and Ubuntu ship venv (and ensurepip) in their own package
        rm -rf .venv
        echo "setup: installing Debian's python3-venv" >&2
        as_root apt-get update -qq
        DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq python3-venv >/dev/null
        python3 -m venv .venv
    fi
fi
# reinstall only when the project's dependencies or the extra changed
stamp=".venv/.gearcoupling-$extra"
want="$(sha256sum pyproject.toml | cut -c1-16)"
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check --upgrade pip >&2
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -e ".[$extra]" >&2
    echo "$want" > "$stamp"
fi
echo "$PWD/.venv/bin/python"
