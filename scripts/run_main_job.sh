#!/usr/bin/env bash
# Installs what is needed, builds, and runs gradem's main job on the bundled data.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/app/gradem lab lab_data/datasets/study --out out/lab
# The calibration of both sands (joint mode) against the lab statistics just written:
# results in out/calibration-joint (summary.json, summary.md, convergence.csv, curves.csv).
# It ends with the path of its report: report: out/calibration-joint/report.html
./build/app/gradem calibrate calibrate/configs/joint.toml
test -f out/calibration-joint/report.html || { echo "main job: no out/calibration-joint/report.html (see the warning above)" >&2; exit 1; }
