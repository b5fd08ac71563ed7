#!/bin/sh
# Cost and macro response, parallel bonds vs explicit paste: the same sands,
# edge (2.5 mm), seed (1) and start [material] (calibration_cube.toml / paste_cube.toml), the
# paste coarse-grained at each size in PASTE_SIZES_MM (coarser than 0.1 mm does not fit the
# pores at solid_fraction 0.3: the fill refuses it). Runs `gradem compress` per case into
# OUT/<case> (a case whose macro.json exists is not re-run: delete it to re-measure), then
# prints one Markdown table (tools: gradem, sed, /usr/bin/python3).
#
#   OMP_NUM_THREADS=2 sh experiments/studies/paste_cost.sh [OUT] [GRADEM]
#   PASTE_SIZES_MM="0.1 0.08" SANDS="pre-blended|Van Buren" ...   (the defaults)
# With CALIBRATIONS="<calibration output folder> ..." the cases are instead the calibrated
# configs those calibrations wrote (calibrated-<sand>.toml: each one's seed-1 test at the
# calibrated parameters), named <folder>_<sand>:
#   CALIBRATIONS="out/calibration-joint-paste-pb-gap out/calibration-joint-paste" \
#       OMP_NUM_THREADS=2 sh experiments/studies/paste_cost.sh out/paste-cost-calibrated
# EDGE_MM=<mm> runs each calibrated config on cubes of that edge instead of its own (a copy in
# OUT with [genesis] edge_mm replaced; the case name ends in _<edge>mm): calibrations fitted on
# different cube sizes compared per cube test of one size.
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
OUT=${1:-$ROOT/out/paste-cost}
GRADEM=${2:-$ROOT/build/app/gradem}
SIZES=${PASTE_SIZES_MM:-"0.1 0.08"}
SANDS=${SANDS:-"pre-blended|Van Buren"}
mkdir -p "$OUT"

# A config in OUT from a shipped one: paths made absolute, the sand (and paste size) set.
make_config() {  # $1 source toml, $2 target, $3 sand, $4 paste size [mm] or ""
    sed -e "s|\"\\.\\./\\.\\./|\"$ROOT/|g" -e "s|^sand = \"[^\"]*\"|sand = \"$3\"|" "$1" > "$2"
    if [ -n "$4" ]; then
        sed -i -e "s|^min_diameter_mm = 0.1 |min_diameter_mm = $4 |" -e "s|^max_diameter_mm = 0.1 |max_diameter_mm = $4 |" "$2"
    fi
}

run_case() {  # $1 case name, $2 config
    if [ ! -f "$OUT/$1/macro.json" ]; then
        echo "paste_cost: running $1 ..." >&2
        "$GRADEM" compress "$2" --out "$OUT/$1" > "$OUT/$1.log" 2>&1 || echo "paste_cost: $1 failed (see $OUT/$1.log)" >&2
    fi
}

CASES=""
if [ -n "${CALIBRATIONS:-}" ]; then
    for dir in $CALIBRATIONS; do
        for cfg in "$dir"/calibrated-*.toml; do
            [ -f "$cfg" ] || { echo "paste_cost: no calibrated-<sand>.toml in $dir (run its calibration first)" >&2; exit 2; }
            name=$(basename "$dir")_$(basename "$cfg" .toml | sed 's/^calibrated-//')
            if [ -n "${EDGE_MM:-}" ]; then
                name=${name}_${EDGE_MM}mm
                sed -e "s|^edge_mm = .*|edge_mm = $EDGE_MM|" "$cfg" > "$OUT/$name.toml"
                cfg=$OUT/$name.toml
            fi
            run_case "$name" "$cfg"
            CASES="$CASES|$name"
        done
    done
else
    IFS='|'
    for sand in $SANDS; do
        tag=$(echo "$sand" | tr -c 'A-Za-z0-9\n' '_')
        make_config "$ROOT/experiments/configs/calibration_cube.toml" "$OUT/pb_$tag.toml" "$sand" ""
        run_case "pb_$tag" "$OUT/pb_$tag.toml"
        CASES="$CASES|pb_$tag"
        IFS=' '
        for d in $SIZES; do
            make_config "$ROOT/experiments/configs/paste_cube.toml" "$OUT/paste${d}_$tag.toml" "$sand" "$d"
            run_case "paste${d}_$tag" "$OUT/paste${d}_$tag.toml"
            CASES="$CASES|paste${d}_$tag"
        done
        IFS='|'
    done
fi
unset IFS

/usr/bin/python3 - "$OUT" "$ROOT/out/lab/lab_results.json" "$CASES" <<'PY'
import json, os, sys
out, lab_file, cases = sys.argv[1], sys.argv[2], [c for c in sys.argv[3].split("|") if c]
lab = {}
if os.path.exists(lab_file):  # written by `gradem lab lab_data/datasets/study --out out/lab`
    for s in json.load(open(lab_file))["sands"]:
        lab[s["name"]] = s
print("| case | sand | particles (paste) | bonds | dt [s] | steps | wall [s] | particle-steps/s | E [GPa] | peak [MPa] | strain at peak |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for c in cases:
    f = os.path.join(out, c, "macro.json")
    if not os.path.exists(f):
        print(f"| {c} | (no result) |||||||||")
        continue
    j = json.load(open(f)); r = j["run"]; sand = j["specimen"]["sand"]
    paste = j.get("paste", {}).get("paste_count", 0)
    fmt = lambda v, s: "n/a" if v is None else s.format(v)
    print(f"| {c} | {sand} | {r['particles']} ({paste}) | {r['bonds']} | {r['time_step_s']:.3g} | {r['steps']} | "
          f"{r['wall_seconds']:.1f} | {fmt(r['particle_steps_per_s'], '{:.3g}')} | {fmt(j['chord_modulus_mpa'] and j['chord_modulus_mpa'] / 1000, '{:.2f}')} | "
          f"{fmt(j['peak_stress_mpa'], '{:.2f}')} | {fmt(j['strain_at_peak'], '{:.5f}')} |")
for name, s in lab.items():
    print(f"| lab | {name} | | | | | | | {s['chord_modulus_mpa']['mean'] / 1000:.2f} | {s['peak_stress_mpa']['mean']:.2f} | {s['strain_at_peak']['mean']:.5f} |")
PY
