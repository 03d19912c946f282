#!/usr/bin/env bash
# What every `cdem` command pays before it starts working: the loader, the libraries' static
# initialisers and their page faults (docs/performance.md "Session 57"). Runs `cdem --help`
# `runs` times (30) and prints the median wall time (ms), minor page faults and peak resident
# size (KB), with the machine's load. Given a second cdem binary (a baseline), alternates the two
# run by run and prints the ratio of the medians. Not a CTest test; run it by hand:
#   bash bench/startup.sh [build-dir] [runs] [baseline-cdem]
set -euo pipefail
fail() { echo "startup.sh: $1" >&2; exit 2; }
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:-$here/../build}"
runs="${2:-30}"
baseline="${3:-}"
cdem="$build/bin/cdem"
[ -x "$cdem" ] || fail "$cdem not found; build first (scripts/setup.sh)"
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || fail "runs must be a positive integer, got '$runs'"
[ -z "$baseline" ] || [ -x "$baseline" ] || fail "baseline '$baseline' is not an executable"
[ -x /usr/bin/time ] || fail "/usr/bin/time not found (Debian package time)"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
echo "startup.sh: $(date -u '+%Y-%m-%d %H:%M:%S') UTC, $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"
binaries=("$cdem")
[ -z "$baseline" ] || binaries+=("$baseline")
# One run of binary b: "wall_ms faults peak_KB" appended to $work/b.
for r in $(seq "$runs"); do
  for b in "${!binaries[@]}"; do
    start=$(date +%s%N)
    /usr/bin/time -o "$work/time" -f "%R %M" "${binaries[$b]}" --help > /dev/null
    end=$(date +%s%N)
    echo "$(((end - start) / 1000)) $(cat "$work/time")" >> "$work/$b"
  done
done
median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
for b in "${!binaries[@]}"; do
  wall=$(cut -d' ' -f1 "$work/$b" | median)
  printf '  %s: median %.1f ms wall, %s minor faults, %s KB peak (%s runs)\n' "${binaries[$b]}" \
    "$(echo "$wall" | awk '{ print $1 / 1000 }')" "$(cut -d' ' -f2 "$work/$b" | median)" \
    "$(cut -d' ' -f3 "$work/$b" | median)" "$runs"
  echo "$wall" > "$work/median_$b"
done
if [ -n "$baseline" ]; then
  printf '  ratio of the medians (this / baseline): %.3f\n' \
    "$(paste "$work/median_0" "$work/median_1" | awk '{ print $1 / $2 }')"
fi
echo "startup.sh: done, load $(cut -d' ' -f1-3 /proc/loadavg)"
