#!/usr/bin/env bash
# Runs `ksmcmc explore` on generated floors (synth seeds 1-5) with explore seeds 1 and 2, and
# prints the BENCHMARKS table: updates, warm and cold iterations, their ratio, and K(W,M) of
# the final world on the full map against a cold run on the full map.
#
#   scripts/explore-table.sh [KSMCMC] [OUT_DIR] [SYNTH_OPTIONS...]
#
# SYNTH_OPTIONS go to every `ksmcmc synth`, e.g. `--wall-thickness 1` for the 1-cell-wall table.
set -euo pipefail
bin=${1:-target/release/ksmcmc}
out=${2:-target/explore-table}
synth_options=("${@:3}")
mkdir -p "$out"
echo "| floor | explore seed | updates | warm | cold | warm/cold | K final (full map) | K cold (full map) |"
echo "|---|---|---|---|---|---|---|---|"
for floor in 1 2 3 4 5; do
  "$bin" synth --seed "$floor" "${synth_options[@]}" --out "$out/synth$floor" >/dev/null
  for seed in 1 2; do
    d="$out/explore$floor-$seed"
    "$bin" explore "$out/synth$floor/map.yaml" --out "$d" --seed "$seed" >/dev/null 2>&1
    python3 - "$d/report.json" "$floor" "$seed" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
w, c = r["warm_iterations"], r["cold_iterations"]
print(f"| synth {sys.argv[2]} | {sys.argv[3]} | {r['updates']} | {w:,} | {c:,} | {w / c:.2f} | "
      f"{r['cell_prediction_rate_on_full_map']:.4f} | {r['cold_full_map']['cell_prediction_rate']:.4f} |")
PY
  done
done
