#!/usr/bin/env bash
# cdem vs LAMMPS on the same unbonded 2D packing for the same number of steps, one core each.
# Not a CTest test: run by hand after building bench_dem_lammps (Release):
#   bash bench/lammps_compare.sh [build-dir] [steps] [repetitions]
# Installs the Debian `lammps` package if `lmp` is missing (needs root). Prints every run, the
# medians and the ratio of time per step per disc (LAMMPS / cdem), in wall time and in CPU time
# (cdem: CPU time of the timing thread; LAMMPS: its loop time x its own "% CPU use"). On a
# shared machine the CPU times are the steadier pair; on a quiet one both agree.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:-$here/../build}"
steps="${2:-1000}"
reps="${3:-5}"

if ! command -v lmp > /dev/null; then
  echo "lmp not found: installing the Debian lammps package" >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y lammps > /dev/null
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The runs alternate, cdem then LAMMPS, so a change in the load of a shared machine hits both
# sides alike. Each cdem run is its own process (it rebuilds the packing first, untimed); the
# first one writes packing.data and params.in into $work for LAMMPS.
cp "$here/lammps_compare.in" "$work/in.compare"
: > "$work/lammps_times"
for rep in $(seq "$reps"); do
  CDEM_LAMMPS_DIR="$work" CDEM_LAMMPS_STEPS="$steps" OMP_NUM_THREADS=1 \
    "$build/bin/bench_dem_lammps" --benchmark_repetitions=1 \
    --benchmark_out="$work/cdem_$rep.json" --benchmark_out_format=json > /dev/null
  (cd "$work" && OMP_NUM_THREADS=1 lmp -in in.compare -log lammps.log -screen none > /dev/null)
  loop="$(sed -n 's/^Loop time of \([0-9.eE+-]*\) on 1 procs for \([0-9]*\) steps with \([0-9]*\) atoms.*/\1 \2 \3/p' \
    "$work/lammps.log")"
  cpu_use="$(sed -n 's/^\([0-9.]*\)% CPU use.*/\1/p' "$work/lammps.log")"
  echo "$loop $cpu_use" >> "$work/lammps_times"
done

python3 - "$work/lammps_times" "$work"/cdem_*.json <<'PY'
import json, statistics, sys
runs = [b for f in sys.argv[2:] for b in json.load(open(f))["benchmarks"]
        if b.get("run_type") == "iteration"]
discs, steps = runs[0]["discs"], runs[0]["steps"]
lines = [line.split() for line in open(sys.argv[1])]
assert int(lines[0][2]) == int(discs), (lines[0][2], discs)
per_step = 1e9 / discs / steps
for label, cdem, lammps in (
        ("wall", [b["real_time"] / 1e3 for b in runs], [float(l[0]) for l in lines]),
        ("CPU", [b["cpu_time"] / 1e3 for b in runs],
         [float(l[0]) * float(l[3]) / 100 for l in lines])):
    c, l = statistics.median(cdem), statistics.median(lammps)
    print(f"{label} time, discs {int(discs)}, steps {int(steps)}, repetitions {len(cdem)} / {len(lammps)}")
    print("  cdem   s:", " ".join(f"{t:.3f}" for t in cdem), f"median {c:.3f}")
    print("  LAMMPS s:", " ".join(f"{t:.3f}" for t in lammps), f"median {l:.3f}")
    print(f"  ns per disc-step: cdem {c * per_step:.1f}, LAMMPS {l * per_step:.1f}")
    print(f"  LAMMPS / cdem time per step per disc: {l / c:.2f} (ratio of the medians); "
          f"median of the {len(lammps)} alternating pairs: "
          f"{statistics.median(b / a for a, b in zip(cdem, lammps)):.2f}")
PY
