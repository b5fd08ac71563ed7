#!/usr/bin/env bash
# Builds the libFuzzer targets of the lab-file readers (clang, ASan + UBSan) in their own build
# directory and runs each for a fixed time, seeded with the test fixtures and bundled data.
# Exits non-zero on a crash, a sanitizer finding, a timeout or a build failure.
#
#   lab_data/fuzz/run_fuzz.sh                 # 20 s per target
#   GRADEM_FUZZ_SECONDS=120 lab_data/fuzz/run_fuzz.sh
# Environment: GRADEM_FUZZ_BUILD (default <repo>/build-fuzz), GRADEM_FUZZ_SECONDS (20),
# GRADEM_FUZZ_JOBS (2). Needs clang++ (Debian: clang, which ships the libFuzzer runtime).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
build="${GRADEM_FUZZ_BUILD:-$repo/build-fuzz}"
seconds="${GRADEM_FUZZ_SECONDS:-20}"
jobs="${GRADEM_FUZZ_JOBS:-2}"
targets=(exports sieve_table tension)

command -v clang++ >/dev/null || { echo "run_fuzz: clang++ not found (apt-get install clang)" >&2; exit 2; }
CXX=clang++ cmake -S "$repo" -B "$build" -DGRADEM_FUZZ=ON -DGRADEM_OPENMP=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_lab_}"

fixtures="$repo/tests/lab_data/fixtures"
study="$repo/lab_data/datasets/study"
status=0
for t in "${targets[@]}"; do
  corpus="$build/fuzz/corpus/$t"
  artifacts="$build/fuzz/artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  if [ "$t" = sieve_table ]; then
    cp "$fixtures"/sieve_*.csv "$fixtures"/sieve_layouts/*.csv "$study"/sieve_*.csv "$study"/astm_c144_*.csv "$corpus"/
  elif [ "$t" = tension ]; then
    cp "$fixtures"/tension/*.csv "$fixtures"/*.csv "$corpus"/
  else
    cp "$fixtures"/*.csv "$fixtures"/*.dat "$corpus"/
    cp "$study"/cubes/PB1-C01.csv "$corpus"/
  fi
  echo "run_fuzz: $t for ${seconds}s"
  if ! "$build/lab_data/fuzz_lab_$t" "$corpus" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
        -rss_limit_mb=2560 -print_final_stats=1 -artifact_prefix="$artifacts/" 2>"$build/fuzz/$t.log"; then
    echo "run_fuzz: $t FAILED (log: $build/fuzz/$t.log, inputs: $artifacts)" >&2
    tail -40 "$build/fuzz/$t.log" >&2
    status=1
  else
    grep -E "stat::number_of_executed_runs|Done" "$build/fuzz/$t.log" | tail -2 || true
  fi
done
exit $status
