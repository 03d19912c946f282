#!/usr/bin/env bash
# The main job on the bundled sample: generate the C30 reference specimen (SPEC section 8) and
# show where the results are.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out
./build/bin/cdem generate samples/c30_specimen.toml -o out/c30_specimen.h5 \
  --summary out/c30_specimen.json --picture out/c30_specimen.png
echo
echo "specimen: out/c30_specimen.h5   (schema: docs/specimen_file.md)"
echo "summary:  out/c30_specimen.json"
echo "picture:  out/c30_specimen.png"
python3 - <<'PY'
import json
s = json.load(open("out/c30_specimen.json"))
print("bins (target/placed):", [(b["target_count"], b["placed_count"]) for b in s["bins"]])
a = s["aggregate_area_fraction"]
print(f"aggregate area fraction: target {a['target']:.4f}, achieved {a['achieved']:.4f}")
print(f"discs {s['discs']}, clumps {s['clumps']}, porosity {s['porosity']:.4f}, "
      f"residual stress {s['residual_stress_MPa']:.4f} MPa, total {s['timings_s']['total']:.1f} s")
PY
