#!/usr/bin/env bash
# Installs what is needed, builds, and runs the default test suite (slow tests, tagged [.slow],
# are skipped; run them with: ./build/tests/<exe> "[slow]").
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build -j"$(nproc)" --output-on-failure
