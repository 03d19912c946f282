#!/usr/bin/env bash
# Interrupted commands (issue 13): `cdem generate` and `cdem run` killed with SIGINT, SIGTERM and
# SIGKILL at random times, 20 tries each. After every kill:
#   - the outputs are all there or none is (one command's outputs are renamed together), and when
#     they are there they are complete: the specimen is byte-identical to an uninterrupted
#     generation with the same seed, the run's summary holds the same peak stress as an
#     uninterrupted run and its result file opens;
#   - after SIGINT or SIGTERM no temporary file is left and the exit status is 128 + signal;
#   - after SIGKILL the temporary file may remain, and the next run of the same command removes
#     it (its process is gone) and completes.
# Kill times are drawn from a seeded generator over 1.2 x the uninterrupted duration. Run by
# CTest (label bad_input) with CDEM and SRC set; needs /usr/bin/python3 with h5py.
set -u
: "${CDEM:?}" "${SRC:?}"
PY=${PYTHON_H5PY:-/usr/bin/python3}
TRIES=${TRIES:-20}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
passed=0
RANDOM=13  # the kill times are the same on every run of the test

cp "$SRC/tests/tiny_specimen.toml" spec.toml
cp "$SRC/samples/c30_materials.toml" materials.toml
printf 'seed = 1\nspecimen = "specimen.h5"\nmaterials = "materials.toml"\n[test]\ntype = "uniaxial"\nsnapshot_interval = 1000\n' > test.toml

gen_cmd=("$CDEM" generate spec.toml -o g.h5 --summary g.json --picture g.png -q)
gen_outputs="g.h5 g.json g.png"
run_cmd=("$CDEM" run test.toml -o r.h5 --summary r.json -q)
run_outputs="r.h5 r.xmf r_bonds.xmf r_cracks.xmf r.json r_stress_strain.png r_cracks.png"

now_ms() { date +%s%3N; }
# The references: uninterrupted runs, timed.
t0=$(now_ms)
"$CDEM" generate spec.toml -o specimen.h5 -q || { echo "FAIL: reference generation"; exit 1; }
t1=$(now_ms)
"${run_cmd[@]}" > /dev/null || { echo "FAIL: reference run"; exit 1; }
t2=$(now_ms)
gen_ms=$((t1 - t0)) run_ms=$((t2 - t1))
cp r.json reference_run.json
rm -f $run_outputs
echo "uninterrupted: generate $gen_ms ms, run $run_ms ms"

peak() { "$PY" -c 'import json,sys; print(json.load(open(sys.argv[1]))["peak_stress_MPa"])' "$1"; }
reference_peak=$(peak reference_run.json)

# complete_generate / complete_run: the outputs exist and are the ones an uninterrupted command
# writes.
complete_generate() {
  cmp -s g.h5 specimen.h5 && "$PY" -c 'import json; json.load(open("g.json"))' 2>/dev/null &&
    [ -s g.png ]
}
complete_run() {
  [ "$(peak r.json 2>/dev/null)" = "$reference_peak" ] &&
    "$PY" -c 'import h5py; h5py.File("r.h5", "r")["history"]' 2>/dev/null && [ -s r.xmf ] &&
    [ -s r_bonds.xmf ] && [ -s r_cracks.xmf ] && [ -s r_stress_strain.png ] && [ -s r_cracks.png ]
}

fail() { echo "FAIL $1"; failures=$((failures + 1)); }

# try NAME SIGNAL DURATION_MS OUTPUTS CHECK COMMAND...
try() {
  local name=$1 sig=$2 duration=$3 outputs=$4 check=$5
  shift 5
  rm -f $outputs
  local delay_ms=$((RANDOM % (duration * 12 / 10 + 1)))
  "$@" > /dev/null 2>&1 &
  local pid=$!
  sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  kill -s "$sig" "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  local rc=$? present=0 total=0
  for o in $outputs; do
    total=$((total + 1))
    [ -e "$o" ] && present=$((present + 1))
  done
  local what="$name $sig at $delay_ms ms (exit $rc, $present of $total outputs)"
  if [ "$present" -ne 0 ] && [ "$present" -ne "$total" ]; then fail "$what: a partial set"; return; fi
  if [ "$present" -eq "$total" ] && ! "$check"; then fail "$what: outputs incomplete"; return; fi
  local temps
  temps=$(find . -name '*.tmp[0-9]*')
  if [ "$sig" != KILL ]; then
    if [ -n "$temps" ]; then fail "$what: left $temps"; return; fi
    if [ "$present" -eq 0 ] && [ "$rc" -ne $((128 + $(kill -l "$sig"))) ]; then
      fail "$what: exit $rc, expected 128 + SIG$sig"; return
    fi
  elif [ -n "$temps" ]; then
    # The next run of the same command clears what the killed one left.
    rm -f $outputs
    if ! "$@" > /dev/null 2>&1; then fail "$what: the next run failed"; return; fi
    local after
    after=$(find . -name '*.tmp[0-9]*')
    if [ -n "$after" ]; then fail "$what: the next run left $after"; return; fi
    if ! "$check"; then fail "$what: the next run's outputs are incomplete"; return; fi
    what="$what; stale $(echo $temps | wc -w) temporary file(s) cleared by the next run"
  fi
  passed=$((passed + 1))
  echo "ok   $what"
}

# Stale temporary files of a process that is gone are removed by the next run of the command;
# those of a live process (this shell) are left alone: it may still be writing them.
true &
dead=$!
wait "$dead"
printf 'stale' > "g.h5.tmp$dead"
printf 'live' > "g.h5.tmp$$"
rm -f $gen_outputs
"${gen_cmd[@]}" || fail "generate beside stale temporary files"
if [ -e "g.h5.tmp$dead" ]; then fail "the temporary file of dead process $dead was not removed"; fi
if [ ! -e "g.h5.tmp$$" ]; then fail "the temporary file of live process $$ was removed"; fi
if ! complete_generate; then fail "generate beside stale temporary files: outputs incomplete"; fi
rm -f "g.h5.tmp$$" $gen_outputs
echo "stale temporary files: the dead process's removed, the live one's kept"

for sig in INT TERM KILL; do
  for ((k = 0; k < TRIES; ++k)); do
    try generate "$sig" "$gen_ms" "$gen_outputs" complete_generate "${gen_cmd[@]}"
    try run "$sig" "$run_ms" "$run_outputs" complete_run "${run_cmd[@]}"
  done
done

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
