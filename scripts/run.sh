#!/usr/bin/env bash
# Set up (idempotent, scripts/setup.sh) and run the main job: `gearcoupling run SPEC` on a
# bundled template or a TOML file (default renzo-1967) -> outputs/<spec>/.
# Other arguments go to `gearcoupling run`.
set -euo pipefail
cd "$(dirname "$0")/.."
python="$(bash scripts/setup.sh all | tail -n 1)"
exec "$python" -m gearcoupling run "${@:-renzo-1967}"
