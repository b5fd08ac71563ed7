#!/usr/bin/env bash
# Resolution effect: peak stress and chord modulus of the default-size and verification-size
# cubes over several packing seeds (same material, same bond seed). Two runs at a time, one
# thread each. Usage: experiments/studies/resolution_study.sh [default seeds] [verification seeds]
# Prints a table and writes out/resolution/summary.csv.
set -euo pipefail
cd "$(dirname "$0")/../.."
default_seeds=${1:-5}
verification_seeds=${2:-2}
mkdir -p out/resolution
run() {  # config size seed
  # Same depth as experiments/configs, so the config's relative paths still hold.
  local cfg="out/resolution/$2-$3.toml"
  sed "0,/^seed = [0-9]*/s//seed = $3/" "experiments/configs/$1" > "$cfg"
  OMP_NUM_THREADS=1 ./build/app/gradem compress "$cfg" --out "out/resolution/$2-$3" > "out/resolution/$2-$3.log" 2>&1 || true
}
jobs=()
for s in $(seq 1 "$default_seeds"); do jobs+=("default_cube.toml default $s"); done
for s in $(seq 1 "$verification_seeds"); do jobs+=("verification_cube.toml verification $s"); done
for ((k = 0; k < ${#jobs[@]}; k += 2)); do
  run ${jobs[k]} &
  if (( k + 1 < ${#jobs[@]} )); then run ${jobs[k+1]} & fi
  wait
done
/usr/bin/python3 - <<'PY'
import glob, json, statistics, os
rows = []
for path in sorted(glob.glob("out/resolution/*/macro.json")):
    size, seed = os.path.basename(os.path.dirname(path)).split("-")
    m = json.load(open(path))
    run = m.get("run", {})
    rows.append((size, int(seed), run.get("particles"), m["peak_stress_mpa"], m["chord_modulus_mpa"], m["strain_at_peak"], run.get("wall_seconds")))
with open("out/resolution/summary.csv", "w") as f:
    f.write("size,seed,particles,peak_stress_mpa,chord_modulus_mpa,strain_at_peak,test_wall_seconds\n")
    for r in rows: f.write(",".join(str(x) for x in r) + "\n")
for size in ("default", "verification"):
    sel = [r for r in rows if r[0] == size]
    if not sel: continue
    for name, k in (("peak stress MPa", 3), ("chord modulus MPa", 4), ("strain at peak", 5)):
        v = [r[k] for r in sel if r[k] is not None]
        sd = statistics.stdev(v) if len(v) > 1 else float("nan")
        print(f"{size:13s} n={len(v)} N~{sel[0][2]} {name:18s} mean {statistics.mean(v):.5g}  std {sd:.3g}")
PY
