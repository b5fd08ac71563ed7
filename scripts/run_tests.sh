#!/usr/bin/env bash
# Installs what is needed, builds, and runs the default test suite (slow tests, tagged [.slow],
# are skipped; run them with: ./build/tests/<exe> "[slow]").
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
# One OpenMP thread per test process and one process per core: OpenMP threads spin-wait, so
# two multi-threaded tests sharing two cores slow each other down several-fold. Tests that
# check thread-count independence set their thread counts themselves.
OMP_NUM_THREADS=1 ctest --test-dir build -j"$(nproc)" --output-on-failure
