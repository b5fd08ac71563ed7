#!/usr/bin/env bash
# Installs what is needed, builds, and runs gradem's main job on the bundled data.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/app/gradem quick-cube --out out/quick-cube
