#!/usr/bin/env bash
# The main job: install, build, run the demo. A window when a display exists; otherwise the
# default scene is rendered headless to out/demo.png. Extra arguments go to weft-demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
source scripts/env.sh
exec "$WEFT_DEMO_EXE" --out out/demo.png "$@"
