#!/usr/bin/env bash
# The same small campaign run locally (-j 2) and under `mpirun -np 2` must give the same
# results.csv (all columns but wall_s), both ranks must have executed runs, and no job may see
# the MPI environment. Run by CTest with CAMPAIGN (binary with the `campaign` subcommand),
# FAKE_JOB (binary with the `fake-job` stand-in) and MPIEXEC set.
set -u
: "${CAMPAIGN:?}" "${FAKE_JOB:?}"
MPIEXEC=${MPIEXEC:-mpirun}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

cat > "$work/base.toml" <<'TOML'
seed = 1
[fake]
x = 0.5
n = 2
fail_above = 0.7
sleep_ms = 150
TOML
# Gathered fields without commas, so that cut can drop the wall_s column below.
cat > "$work/campaign.toml" <<TOML
base = "base.toml"
seeds = [1, 2]
gather = ["y", "nested.n", "mpi_env"]
[job]
executable = "$FAKE_JOB"
command = "fake-job"
args = ["{input}", "--summary", "{summary}", "--seed", "{seed}", "--log", "{dir}/../../log.txt"]
outputs = ["output.dat"]
timeout_s = 60
[design]
type = "full_factorial"
[[factors]]
key = "fake.x"
values = [0.2, 0.5, 0.8]
[[factors]]
key = "fake.n"
low = 1
high = 3
TOML

timeout 120 "$CAMPAIGN" campaign "$work/campaign.toml" -j 2 -o "$work/local" 2>"$work/local.err" \
  || { cat "$work/local.err"; fail "local campaign exited $?"; }

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Containers often forbid the cross-memory attach Open MPI's shared-memory transport uses for
# larger messages (a task carries a whole input file); plain copies work everywhere.
export OMPI_MCA_btl_vader_single_copy_mechanism=none
timeout 180 "$MPIEXEC" --allow-run-as-root --oversubscribe -np 2 \
  "$CAMPAIGN" campaign "$work/campaign.toml" -o "$work/mpi" >"$work/mpi.out" 2>"$work/mpi.err" \
  || { cat "$work/mpi.out" "$work/mpi.err"; fail "mpirun campaign exited $?"; }

without_wall() {
  local col
  col=$(head -1 "$1" | tr ',' '\n' | grep -n '^wall_s$' | cut -d: -f1)
  [ -n "$col" ] || fail "no wall_s column in $1"
  cut -d, -f"$col" --complement "$1"
}
without_wall "$work/local/results.csv" > "$work/local.csv"
without_wall "$work/mpi/results.csv" > "$work/mpi.csv"
diff "$work/local.csv" "$work/mpi.csv" || fail "results.csv differs between local and MPI runs"
rows=$(($(wc -l < "$work/mpi.csv") - 1))
[ "$rows" -eq 12 ] || fail "expected 12 rows, got $rows"
grep -q ',failed,' "$work/mpi.csv" || fail "the failing runs are missing"
grep -q ',true,' "$work/mpi.csv" && fail "a job saw the MPI environment"
ranks=$(awk '{print $3}' "$work/mpi/log.txt" | sort -u | wc -l)
[ "$ranks" -eq 2 ] || fail "expected runs on 2 ranks, got $ranks"
grep -q "MPI: 2 ranks" "$work/mpi.err" || { cat "$work/mpi.err"; fail "no MPI report"; }
# Started again, the MPI campaign finds every run complete and executes nothing.
lines=$(wc -l < "$work/mpi/log.txt")
timeout 120 "$MPIEXEC" --allow-run-as-root --oversubscribe -np 2 \
  "$CAMPAIGN" campaign "$work/campaign.toml" -o "$work/mpi" >"$work/again.out" 2>"$work/again.err" \
  || { cat "$work/again.out" "$work/again.err"; fail "second mpirun campaign exited $?"; }
grep -q "12 already complete, 0 to run" "$work/again.err" || { cat "$work/again.err"; fail "no reuse"; }
[ "$(wc -l < "$work/mpi/log.txt")" -eq "$lines" ] || fail "completed runs were executed again"

# A bad campaign file under mpirun: rank 0 reports it and releases the workers; no hang.
sed 's/^key = "fake.n"/key = "fake.m"/' "$work/campaign.toml" > "$work/bad.toml"
timeout 120 "$MPIEXEC" --allow-run-as-root --oversubscribe -np 2 \
  "$CAMPAIGN" campaign "$work/bad.toml" -o "$work/bad" >"$work/bad.out" 2>"$work/bad.err"
rc=$?
[ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || { cat "$work/bad.err"; fail "bad file under mpirun: exit $rc"; }
grep -q "key 'factors\[1\].key'" "$work/bad.err" || { cat "$work/bad.err"; fail "bad file message"; }

echo "ok: local and MPI results.csv agree ($rows runs, executed by $ranks ranks)"

