#!/usr/bin/env bash
# The result file's XDMF companions open in a real reader (issue 14, points 3 and 4): meshio
# (Debian python3-meshio) reads the discs and the bond network as temporal collections, every
# snapshot, and the crack log as one grid; counts and attributes must equal the HDF5 datasets
# read with h5py. A uniaxial test of the tiny specimen with parallel bonds and snapshots every
# 2,000 steps. Run by CTest with CDEM and SRC set.
set -euo pipefail
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
cp "$SRC/tests/tiny_specimen.toml" spec.toml
cp "$SRC/samples/c30_materials.toml" materials.toml
"$CDEM" generate spec.toml -o specimen.h5 -q
printf 'seed = 1\nspecimen = "specimen.h5"\nmaterials = "materials.toml"\n[test]\ntype = "uniaxial"\nsnapshot_interval = 2000\n' > test.toml
"$CDEM" run test.toml -o result.h5 -q
/usr/bin/python3 "$SRC/tests/xdmf_meshio.py" result
# The smooth joints' XDMF file (docs/result_file.md): the same test with a bonded joint family
# of dip 45 degrees through the centre and a frictional segment.
cat test.toml - > jointed.toml <<'TOML'
[[test.joints]]
dip_deg = 45
spacing_mm = 1000
sj_normal_stiffness_GPa_m = 100
sj_shear_stiffness_GPa_m = 69
sj_tensile_strength_MPa = 0.5
sj_cohesion_MPa = 0.5
sj_friction_angle_deg = 15
sj_friction = 0.27
[[test.joints]]
points_mm = [[0, 15], [20, 15]]
sj_normal_stiffness_GPa_m = 100
sj_shear_stiffness_GPa_m = 69
sj_friction = 0.5
sj_bonded = false
TOML
"$CDEM" run jointed.toml -o jointed.h5 -q
/usr/bin/python3 "$SRC/tests/xdmf_meshio_joints.py" jointed result
