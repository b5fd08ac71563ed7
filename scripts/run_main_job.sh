#!/usr/bin/env bash
# Installs what is needed, builds, and runs gradem's main job on the bundled data.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/app/gradem lab lab_data/datasets/study --out out/lab
./build/app/gradem compress experiments/configs/default_cube.toml
