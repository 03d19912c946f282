#!/usr/bin/env bash
# Does a change of the generator's recipe change the concrete? The C30 specimen of
# samples/c30_specimen.toml is generated with the default recipe and with the variant's keys, on
# the same seeds (the same aggregates and random start), and each specimen is loaded by the UCS
# of samples/c30_ucs.toml; the script then compares the pairs seed by seed (paired t-test and
# Wilcoxon signed-rank test, scipy). Used in session 68 (docs/performance.md "Session 68").
#   bash bench/recipe_material.sh BUILD_DIR OUT_DIR "SEEDS" TABLE.KEY=VALUE [TABLE.KEY=VALUE ...]
#   bash bench/recipe_material.sh build out/recipe "$(seq -s ' ' 10)" mortar.time_step_safety=1.0
# Each KEY = VALUE is written at the top of its [TABLE] of the variant's generator input. Runs
# whose summary exists in OUT_DIR are not run again (an interrupted study resumes; another study
# in the same OUT_DIR is refused, exit 2). Two UCS runs go side by side, one thread each, when
# the process may use two CPUs or more. Ten seeds take about 13-17 minutes on two Zen 3 vCPUs.
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '2,12p' "$0" >&2
  exit 2
fi
src="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "$1" && pwd)"
out="$2"
seeds="$3"
shift 3
cdem="$build/bin/cdem"
[ -x "$cdem" ] || { echo "recipe_material.sh: no $cdem (build first)" >&2; exit 2; }
[ -n "${seeds// /}" ] || { echo "recipe_material.sh: no seeds given" >&2; exit 2; }
for s in $seeds; do
  [[ "$s" =~ ^[0-9]+$ ]] || { echo "recipe_material.sh: seed '$s' is not a whole number" >&2; exit 2; }
done
mkdir -p "$out"
out="$(cd "$out" && pwd)"

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cp "$src/samples/c30_specimen.toml" "$tmp/default.toml"
cp "$src/samples/c30_specimen.toml" "$tmp/variant.toml"
for kv in "$@"; do
  if [[ ! "$kv" =~ ^([a-z_]+)\.([a-z_0-9]+)=(.+)$ ]]; then
    echo "recipe_material.sh: '$kv' is not TABLE.KEY=VALUE (for example mortar.time_step_safety=1.0)" >&2
    exit 2
  fi
  table="${BASH_REMATCH[1]}" key="${BASH_REMATCH[2]}" value="${BASH_REMATCH[3]}"
  grep -q "^\[$table\]" "$tmp/variant.toml" ||
    { echo "recipe_material.sh: samples/c30_specimen.toml has no [$table] table" >&2; exit 2; }
  value="${value//\\/\\\\}" value="${value//\//\\/}" value="${value//&/\\&}"
  sed -i "s/^\[$table\]\$/[$table]\n$key = $value/" "$tmp/variant.toml"
done
# A study resumes only with the inputs it was started with: the runs already in OUT_DIR are
# reused, so other keys (or a changed sample) there would mix two studies.
for recipe in default variant; do
  if [ -f "$out/$recipe.toml" ] && ! cmp -s "$tmp/$recipe.toml" "$out/$recipe.toml"; then
    echo "recipe_material.sh: $out holds a study with another $recipe input ($out/$recipe.toml);" \
      "give another OUT_DIR" >&2
    exit 2
  fi
  cp "$tmp/$recipe.toml" "$out/$recipe.toml"
done

ucs_input() {  # recipe seed -> the UCS input for that specimen
  sed -e "s#^specimen = .*#specimen = \"$out/$1_$2.h5\"#" \
    -e "s#^materials = .*#materials = \"$src/samples/c30_materials.toml\"#" \
    -e 's#^snapshot_interval = .*#snapshot_interval = 0#' "$src/samples/c30_ucs.toml" \
    > "$out/ucs_$1_$2.toml"
}
mapfile -t cpus < <(taskset -pc $$ | sed 's/.*: //' | tr ',' '\n' |
  while IFS=- read -r a b; do seq "$a" "${b:-$a}"; done)
for s in $seeds; do
  for recipe in variant default; do  # the variant first: cdem names a bad key before any long run
    [ -f "$out/${recipe}_$s.json" ] ||
      "$cdem" generate "$out/$recipe.toml" --seed "$s" -o "$out/${recipe}_$s.h5" \
        --summary "$out/${recipe}_$s.json" -q
    ucs_input "$recipe" "$s"
  done
  pids=()
  i=0
  for recipe in default variant; do
    [ -f "$out/ucs_${recipe}_$s.json" ] && continue
    pin=()
    [ "${#cpus[@]}" -ge 2 ] && pin=(taskset -c "${cpus[$i]}")
    "${pin[@]}" "$cdem" run "$out/ucs_${recipe}_$s.toml" --seed "$s" -o "$out/ucs_${recipe}_$s.h5" \
      --summary "$out/ucs_${recipe}_$s.json" -q &
    pids+=($!)
    i=$((i + 1))
    [ "${#cpus[@]}" -ge 2 ] || wait "${pids[-1]}"
  done
  for p in "${pids[@]}"; do wait "$p"; done
  echo "seed $s done $(date -u +%T), load $(cut -d' ' -f1-3 /proc/loadavg)" >&2
done

/usr/bin/python3 - "$out" "$seeds" <<'PY'
import json, os, statistics, sys
from scipy import stats
out, seeds = sys.argv[1], [int(s) for s in sys.argv[2].split()]
def row(recipe, s):
    g = json.load(open(os.path.join(out, f"{recipe}_{s}.json")))
    u = json.load(open(os.path.join(out, f"ucs_{recipe}_{s}.json")))
    p, gen = g["packing"], u["genesis"]
    return {"sigma_u MPa": u["peak_stress_MPa"], "E GPa": u["young_modulus_GPa"],
            "nu": u["poisson_ratio"], "coordination": p["coordination_number"],
            "floating %": 100 * p["floating_discs"] / g["discs"], "cycles": p["steps"],
            "bonds per disc": sum(gen["bonds"].values()) / gen["discs"]}
d = [row("default", s) for s in seeds]
v = [row("variant", s) for s in seeds]
print("seed " + " ".join(f"{k:>22}" for k in d[0]) + "   (default / variant)")
for s, a, b in zip(seeds, d, v):
    print(f"{s:4d} " + " ".join(f"{a[k]:10.5g} / {b[k]:<9.5g}" for k in a))
print(f"over {len(seeds)} seeds: mean default, mean variant, paired difference, t, p"
      + (", Wilcoxon p" if len(seeds) >= 6 else ""))
for k in d[0]:
    x, y = [r[k] for r in d], [r[k] for r in v]
    diff = [b - a for a, b in zip(x, y)]
    if len(seeds) < 2 or all(dv == 0 for dv in diff):
        print(f"  {k:15s} {statistics.mean(x):.5g} {statistics.mean(y):.5g} "
              f"{statistics.mean(diff):+.4g}")
        continue
    t = stats.ttest_rel(y, x)
    w = f" {stats.wilcoxon(y, x).pvalue:.3g}" if len(seeds) >= 6 else ""
    print(f"  {k:15s} {statistics.mean(x):.5g} {statistics.mean(y):.5g} "
          f"{statistics.mean(diff):+.4g} (variant lower on {sum(dv < 0 for dv in diff)} of {len(diff)}) "
          f"t {t.statistic:.2f} p {t.pvalue:.3g}{w}")
PY
