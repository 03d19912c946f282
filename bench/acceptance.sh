#!/usr/bin/env bash
# The speed figures of issue 18's acceptance in one run (docs/performance.md, "Issue 18 at a
# glance"), with the machine's load before every run. Not a CTest test: run it by hand on a
# quiet machine, after building (Release):
#   bash bench/acceptance.sh [build-dir] [rounds] [large-specimen.h5]
# 0. bench_host_caches: the memory latency each CPU sees by working-set size, before and after
#    the runs (on a shared or paravirtualised host the CPUs can differ, and change within
#    minutes; docs/performance.md "Session 38"). Every one-thread run below is pinned to one CPU
#    (`taskset`), round r to the r-th allowed CPU in turn, and says which; the summary gives the
#    one-thread medians per CPU too.
# 1. `cdem generate samples/c30_specimen.toml`, 1 and 2 threads alternated, `rounds` rounds (3):
#    wall, user and peak resident size per run, medians; every specimen must be byte-identical,
#    and its coordination, floating fraction, residual stress and porosity inside the ranges the
#    stability suite asserts (tests/stability/test_stability_packing.cpp).
# 2. samples/c30_ucs.toml on that specimen, `[test] threads` 1 and 2 alternated: wall per run,
#    medians and their ratio; every run must give the same peak stress and steps, bit for bit.
# 3. bench/lammps_compare.sh (1,000 steps, 5 pairs): LAMMPS / cdem per disc-step.
# 4. bench_scale, one thread pinned to the first allowed CPU: the C30 specimen (1,000 steps) and
#    the same specimen tiled 7 x 7 (1,043,945 discs, 300 steps), alternated `rounds` times (the
#    10^6 step as sessions 38-44 measured it, docs/performance.md), each run the median of 3
#    repeats; ns per disc-step, solver bytes per disc, the medians and the 10^6 / C30 ratio of
#    the medians and of each round. And once the large specimen if one is given (e.g. one made
#    with `cdem generate bench/bench_scale_million.toml`, 50 steps).
# Exits non-zero if a run fails or a bitwise or statistics check does not hold. Writes only into
# a temporary directory, removed at exit. Installs the Debian `time` package if /usr/bin/time is
# missing, and bench/lammps_compare.sh the `lammps` package (both need root).
set -euo pipefail
fail() { echo "acceptance.sh: $2" >&2; exit "$1"; }  # exit code, message
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/.." && pwd)"
[ -d "${1:-$repo/build}" ] || fail 2 "build directory '${1:-$repo/build}' not found"
build="$(cd "${1:-$repo/build}" && pwd)"
rounds="${2:-3}"
large="${3:-}"
cdem="$build/bin/cdem"
for exe in "$cdem" "$build/bin/bench_scale" "$build/bin/bench_dem_lammps" \
  "$build/bin/bench_host_caches"; do
  [ -x "$exe" ] || fail 2 "$exe not found; build first (scripts/setup.sh)"
done
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || fail 2 "rounds must be a positive integer, got '$rounds'"
[ -z "$large" ] || [ -f "$large" ] || fail 2 "large specimen '$large' not found"
if [ ! -x /usr/bin/time ]; then  # GNU time: wall, user and peak resident size of each run
  echo "/usr/bin/time not found: installing the Debian time package" >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y time > /dev/null
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
load() { cut -d' ' -f1-3 /proc/loadavg; }
version="$(git -C "$repo" describe --always --dirty 2> /dev/null || echo 'no git')"
echo "acceptance.sh: $(date -u '+%Y-%m-%d %H:%M:%S') UTC, $(nproc) CPUs, load $(load), $version"

echo "== 0. memory latency per CPU (bench_host_caches, ns per dependent load)"
"$build/bin/bench_host_caches" | sed 's/^/  /'
read -r -a cpus <<< "$(taskset -pc $$ | sed 's/.*: //' | tr ',' '\n' |
  awk -F- '{ for (c = $1; c <= ($2 == "" ? $1 : $2); ++c) printf "%d ", c }')"
# run KIND THREADS ROUND COMMAND...: times one run (one thread: pinned to the round's CPU; two:
# wherever the scheduler puts them, cpu "any") into $work/times and prints it.
run() {
  local kind="$1" t="$2" r="$3" cpu=any l
  shift 3
  local pin=()
  if [ "$t" = 1 ]; then
    cpu="${cpus[$(((r - 1) % ${#cpus[@]}))]}"
    pin=(taskset -c "$cpu")
  fi
  l="$(load)"
  /usr/bin/time -o "$work/time" -f "%e %U %M" "${pin[@]}" "$@" > /dev/null
  echo "$kind $t $r $(cat "$work/time") $cpu" >> "$work/times"
  echo "  round $r, $t thread(s) on cpu $cpu, load before $l: $(cat "$work/time")"
}

echo "== 1. cdem generate samples/c30_specimen.toml (wall s, user s, peak KB)"
for r in $(seq "$rounds"); do
  for t in 1 2; do
    run generate "$t" "$r" "$cdem" generate "$repo/samples/c30_specimen.toml" \
      -o "$work/gen_${t}_$r.h5" --summary "$work/gen_${t}_$r.json" --threads "$t" -q
  done
done
for f in "$work"/gen_*.h5; do
  cmp -s "$f" "$work/gen_1_1.h5" || fail 1 "$f differs from gen_1_1.h5"
done
echo "  all $((2 * rounds)) specimens byte-identical"

echo "== 2. samples/c30_ucs.toml, [test] threads = 1 and 2 (wall s)"
for t in 1 2; do
  sed -e "s#^specimen = .*#specimen = \"$work/gen_1_1.h5\"#" \
      -e "s#^materials = .*#materials = \"$repo/samples/c30_materials.toml\"#" \
      -e "s#^\[test\]#[test]\nthreads = $t#" "$repo/samples/c30_ucs.toml" > "$work/ucs_$t.toml"
done
for r in $(seq "$rounds"); do
  for t in 1 2; do
    run ucs "$t" "$r" "$cdem" run "$work/ucs_$t.toml" -o "$work/ucs.h5" \
      --summary "$work/ucs_${t}_$r.json" -q
    rm -f "$work"/ucs.h5 "$work"/ucs.xmf "$work"/ucs*.png
  done
done

echo "== 3. bench/lammps_compare.sh $build 1000 5"
echo "  load before $(load)"
bash "$here/lammps_compare.sh" "$build" 1000 5 > "$work/lammps.out" 2> "$work/lammps.err" ||
  { cat "$work/lammps.err" >&2; exit 1; }
sed -n '/^wall time/,/^CPU time/p' "$work/lammps.out" | sed '$d' | sed 's/^/  /'

echo "== 4. bench_scale (one thread, cpu ${cpus[0]})"
scale() {  # specimen steps [bench_scale options] -> the RESULT line
  echo "  load before $(load)" >&2
  taskset -c "${cpus[0]}" "$build/bin/bench_scale" "$1" --steps "$2" --repeats 3 "${@:3}" |
    grep '^RESULT'
}
for r in $(seq "$rounds"); do
  scale "$work/gen_1_1.h5" 1000 | tee "$work/scale_c30_$r" | sed "s/^/  round $r, C30: /"
  scale "$work/gen_1_1.h5" 300 --tile 7 7 | tee "$work/scale_tiled_$r" |
    sed "s/^/  round $r, C30 tiled 7 x 7: /"
done
[ -z "$large" ] || scale "$large" 50 | tee "$work/scale_large" | sed 's/^/  large: /'

/usr/bin/python3 - "$work" <<'PY'
import glob, json, os, statistics, sys
work = sys.argv[1]
runs = {}
for line in open(os.path.join(work, "times")):
    kind, threads, _, wall, user, peak, cpu = line.split()
    runs.setdefault((kind, int(threads)), []).append((float(wall), float(user), int(peak), cpu))
med = {k: statistics.median(w for w, _, _, _ in v) for k, v in runs.items()}
ok = True
print("== summary (medians of the walls)")
for kind, target in (("generate", "3 s"), ("ucs", "45 s on 1 thread, 30 s on 2, 1.7x")):
    print(f"  {kind}: 1 thread {med[(kind, 1)]:.2f} s, 2 threads {med[(kind, 2)]:.2f} s, "
          f"{med[(kind, 1)] / med[(kind, 2)]:.2f}x (target {target}); peak "
          f"{max(p for _, _, p, _ in runs[(kind, 1)]) / 1024:.1f} / "
          f"{max(p for _, _, p, _ in runs[(kind, 2)]) / 1024:.1f} MB")
    by_cpu = {}
    for wall, _, _, cpu in runs[(kind, 1)]:
        by_cpu.setdefault(cpu, []).append(wall)
    print(f"    1 thread by cpu: " + ", ".join(
        f"cpu {cpu} {statistics.median(w):.2f} s ({len(w)} run{'s' if len(w) > 1 else ''})"
        for cpu, w in sorted(by_cpu.items())))
# The ranges the stability suite asserts (tests/stability/test_stability_packing.cpp,
# ReferenceMould: floating discs over the packing's discs, sigma0 and its tolerance as in
# samples/c30_specimen.toml).
s = json.load(open(os.path.join(work, "gen_1_1.json")))
p = s["packing"]
floating = p["floating_discs"] / s["discs"]
checks = [("coordination > 3.5", p["coordination_number"] > 3.5),
          ("floating < 10 %", floating < 0.10),
          ("residual stress within 5 % of 0.1 MPa", abs(s["residual_stress_MPa"] - 0.1) <= 0.005),
          ("porosity 0.13-0.22", 0.13 <= s["porosity"] <= 0.22)]
print(f"  specimen: coordination {p['coordination_number']:.3f}, floating {100 * floating:.2f} %, "
      f"residual stress {s['residual_stress_MPa']:.4f} MPa, porosity {s['porosity']:.4f}: "
      + ", ".join(f"{name} {'yes' if good else 'NO'}" for name, good in checks))
ok = ok and all(good for _, good in checks)
ucs = {(json.dumps([d["peak_stress_MPa"], d["steps"]]))
       for d in (json.load(open(f)) for f in glob.glob(os.path.join(work, "ucs_*_*.json")))}
print(f"  UCS peak stress and steps over all runs: {sorted(ucs)}"
      f"{' (bitwise the same)' if len(ucs) == 1 else ' DIFFER'}")
ok = ok and len(ucs) == 1
def result(name):
    path = os.path.join(work, name)
    if not os.path.exists(path):
        return None
    fields = open(path).read().split()[1:]
    return dict(zip(fields[::2], fields[1::2]))
rounds = sorted(int(f.rsplit("_", 1)[1]) for f in glob.glob(os.path.join(work, "scale_c30_*")))
c30 = [result(f"scale_c30_{r}") for r in rounds]
tiled = [result(f"scale_tiled_{r}") for r in rounds]
c30_ns = statistics.median(float(c["ns_wall"]) for c in c30)
tiled_ns = statistics.median(float(t["ns_wall"]) for t in tiled)
print(f"  C30 step: {c30_ns:.2f} ns per disc-step (median of {len(rounds)}), "
      f"{c30[0]['accounted_B_per_disc']} B per disc")
print(f"  C30 tiled 7 x 7: {tiled[0]['discs']} discs, {tiled_ns:.2f} ns per disc-step (median), "
      f"{tiled_ns / c30_ns:.2f}x C30 (target within 1.25x; by round "
      + ", ".join(f"{float(t['ns_wall']) / float(c['ns_wall']):.2f}" for c, t in zip(c30, tiled))
      + f"), {tiled[0]['accounted_B_per_disc']} B per disc (target 600)")
large = result("scale_large")
if large:
    print(f"  large step: {large['discs']} discs, {large['ns_wall']} ns per disc-step "
          f"({float(large['ns_wall']) / c30_ns:.2f}x C30; target within 1.25x), "
          f"{large['accounted_B_per_disc']} B per disc (target 600)")
sys.exit(0 if ok else 1)
PY
echo "== memory latency per CPU again, after the runs (ns per dependent load)"
"$build/bin/bench_host_caches" | sed 's/^/  /'
echo "acceptance.sh: done, load $(load)"
