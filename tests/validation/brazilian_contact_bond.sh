#!/usr/bin/env bash
# Validation (label `validation`, issue 13 point 1): the contact-bonded Brazilian disc must give
# a splitting strength proportional to the bonds' tensile strength, sigma_t = k sigma_cn (SPEC 7:
# with every other parameter fixed, the strength of a bonded assembly scales with its bond
# strength), and the stop rule must not end a run at the first bond failure.
# D 50 mm mortar-only disc, R_min 0.3 mm, R_max / R_min = 1, 2, 3, 4; E* 10 GPa, kn/ks 3.5,
# mu 1.7, tau_cs 50 MPa; sigma_cn = 5, 15, 30 MPa. Per ratio: every run ends at a confirmed
# post-peak drop or split with >= 10 cracks, and the fit through the origin has R2 > 0.99
# (R2 = 1 - SS_res / SS_tot, SS_tot about the mean of sigma_t). About 5 min of CPU.
# PLATENS (default flat) is the test's `platens`: flat, curved_jaws or loading_arc
# (docs/lab_tests.md "Brazilian disc").
# Usage: CDEM=path/to/cdem WORK=scratch/dir [PLATENS=loading_arc] bash brazilian_contact_bond.sh
set -euo pipefail
: "${CDEM:?set CDEM to the cdem binary}"
PLATENS=${PLATENS:-flat}
case "$PLATENS" in flat|curved_jaws|loading_arc) ;; *)
  echo "brazilian_contact_bond.sh: PLATENS '$PLATENS' (allowed: flat, curved_jaws, loading_arc)" >&2
  exit 2 ;; esac
WORK=${WORK:-$(mktemp -d)}
mkdir -p "$WORK"
cd "$WORK"

for ratio in 1 2 3 4; do
  r_mean=$(python3 -c "print(0.3 * (1 + $ratio) / 2)")
  cat > "gen_r$ratio.toml" <<TOML
seed = 1
[specimen]
shape = "disc"
diameter_mm = 50
[mortar]
r_mean_mm = $r_mean
r_ratio = $ratio
porosity = 0.12
TOML
  [ -f "spec_r$ratio.h5" ] || "$CDEM" generate "gen_r$ratio.toml" -o "spec_r$ratio.h5" -q
  for sigma_cn in 5 15 30; do
    cat > "t_r${ratio}_s$sigma_cn.toml" <<TOML
seed = 1
specimen = "spec_r$ratio.h5"
[materials.mortar]
law = "contact_bond"
emod_GPa = 10
kratio = 3.5
friction = 1.7
cb_tensile_strength_MPa = $sigma_cn
cb_shear_strength_MPa = 50
[materials.itz]
law = "linear"
emod_GPa = 10
kratio = 3.5
friction = 1.7
[materials.aggregate]
law = "linear"
emod_GPa = 20
kratio = 2
friction = 1.0
[test]
type = "brazilian"
platen_velocity_m_s = 0.02
max_steps = 2000000
platens = "$PLATENS"
TOML
    "$CDEM" run "t_r${ratio}_s$sigma_cn.toml" --summary "o_r${ratio}_s$sigma_cn.json" -q
  done
done

python3 - <<'PY'
import json, sys
ok = True
for ratio in (1, 2, 3, 4):
    xs, ys = [], []
    for s in (5, 15, 30):
        d = json.load(open(f"o_r{ratio}_s{s}.json"))
        cracks = d["cracks"]["total"]
        print(f"ratio {ratio} sigma_cn {s} MPa: sigma_t {d['tensile_strength_MPa']:.4f} MPa, "
              f"{cracks} cracks, {d['steps']} steps, stop {d['stop_reason']}")
        if d["stop_reason"] not in ("post_peak_drop", "split") or cracks < 10:
            print("  FAIL: not a confirmed failure with >= 10 cracks"); ok = False
        xs.append(s); ys.append(d["tensile_strength_MPa"])
    k = sum(x * y for x, y in zip(xs, ys)) / sum(x * x for x in xs)
    mean = sum(ys) / len(ys)
    r2 = 1 - sum((y - k * x) ** 2 for x, y in zip(xs, ys)) / sum((y - mean) ** 2 for y in ys)
    print(f"ratio {ratio}: sigma_t = {k:.4f} sigma_cn, R2 {r2:.4f}")
    if not r2 > 0.99:
        print("  FAIL: R2 <= 0.99"); ok = False
sys.exit(0 if ok else 1)
PY
