#!/usr/bin/env bash
# Same input and seed, same bytes: `cdem generate` twice with the same seed writes identical
# specimen files (cmp), in different folders, at different times and on 1 or 2 threads (HDF5 would store each
# object's creation time unless told not to). A third generation with another seed must differ,
# so the comparison can fail. The same for `cdem run`: the result file of a uniaxial test on
# that specimen, run twice at different times, is byte-identical (no
# modification times, no wall-clock time in it); a stronger mortar must change it. Run by CTest
# with CDEM and SRC set.
set -eu
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
cp "$SRC/tests/tiny_specimen.toml" spec.toml
mkdir first second
"$CDEM" generate spec.toml -o first/specimen.h5 --seed 7 -q
sleep 1.1  # HDF5 timestamps have a resolution of one second
"$CDEM" generate spec.toml -o second/specimen.h5 --seed 7 -q
"$CDEM" generate spec.toml -o other_seed.h5 --seed 8 -q
cmp first/specimen.h5 second/specimen.h5
# The packing's cycles on two threads (--threads, mortar.threads): the same bytes.
mkdir two_threads
"$CDEM" generate spec.toml -o two_threads/specimen.h5 --seed 7 --threads 2 -q
cmp first/specimen.h5 two_threads/specimen.h5
if cmp -s first/specimen.h5 other_seed.h5; then
  echo "FAIL: seeds 7 and 8 gave the same bytes"
  exit 1
fi
echo "ok: two generations with seed 7 (one on 2 threads) are byte-identical ($(stat -c %s first/specimen.h5) bytes); seed 8 differs"

sed -e 's/^pb_moment_factor = 1 /pb_moment_factor = 0 /' "$SRC/samples/c30_materials.toml" > materials.toml
grep -q '^pb_moment_factor = 0 ' materials.toml || { echo "FAIL: no pb_moment_factor to change"; exit 1; }
printf 'seed = 1\nspecimen = "first/specimen.h5"\nmaterials = "materials.toml"\n[test]\ntype = "uniaxial"\nsnapshot_interval = 2000\n' > test.toml
"$CDEM" run test.toml -o first/result.h5 -q
sleep 1.1
"$CDEM" run test.toml -o second/result.h5 -q
if ! cmp first/result.h5 second/result.h5; then
  echo "FAIL: the same test run twice gave different result files"; exit 1
fi
cp "$SRC/samples/c30_materials.toml" materials.toml
"$CDEM" run test.toml -o other_material.h5 -q
if cmp -s first/result.h5 other_material.h5; then
  echo "FAIL: another material gave the same result file"; exit 1
fi
echo "ok: a uniaxial result file run twice is byte-identical ($(stat -c %s first/result.h5) bytes); another material differs"
