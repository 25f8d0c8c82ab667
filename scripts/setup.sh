#!/usr/bin/env bash
# Make the project's virtual environment .venv if it is missing and install the project into
# it with the extra given (default: all). Works where the system python3 refuses pip
# (PEP 668, Debian and Ubuntu) and where python3 is already a venv or pyenv.
# Says what it does before the long install, and a line every 15 s while pip works
# (GEARCOUPLING_SETUP_HEARTBEAT=SECONDS changes the interval).
# Prints the path of the environment's python on its last line.
set -euo pipefail
cd "$(dirname "$0")/.."
extra="${1:-all}"
as_root() { if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi; }
# reinstall only when the project's dependencies or the extra changed
stamp=".venv/.gearcoupling-$extra"
want="$(sha256sum pyproject.toml | cut -c1-16)"
if [ -x .venv/bin/python ] && [ "$(cat "$stamp" 2>/dev/null)" = "$want" ]; then
    echo "$PWD/.venv/bin/python"
    exit 0
fi
echo "setup: setting up .venv: installing gearcoupling and its dependencies (extra '$extra';" \
     "about 1-2 minutes the first time, then again only when pyproject.toml changes)..." >&2
# the heartbeat: a line every interval until this script ends (its EXIT trap stops it, and
# it stops by itself once this script is gone); its output to stderr only, so that the
# caller's pipe on stdout closes with this script
every="${GEARCOUPLING_SETUP_HEARTBEAT:-15}"
(
    trap 'kill "${nap:-}" 2>/dev/null; exit 0' TERM
    start=$SECONDS
    while :; do
        sleep "$every" &
        nap=$!
        wait "$nap"
        kill -0 "$$" 2>/dev/null || exit 0
        echo "setup: still installing ($((SECONDS - start)) s)..."
    done
) >&2 &
beat=$!
trap 'kill "$beat" 2>/dev/null || true' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
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
.venv/bin/python -m pip install --quiet --disable-pip-version-check --upgrade pip >&2
.venv/bin/python -m pip install --quiet --disable-pip-version-check -e ".[$extra]" >&2
echo "$want" > "$stamp"
echo "setup: .venv is ready" >&2
echo "$PWD/.venv/bin/python"
