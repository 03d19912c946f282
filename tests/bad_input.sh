#!/usr/bin/env bash
# Hostile input to every cdem command (issue 13): outputs that would clobber an input or each
# other, outputs that are not regular files, folders that cannot hold an output, corrupt values
# in a specimen file, campaign and calibration files that must be refused before any job starts.
# Each case must exit 2 or 3, name the file and the key (or dataset or option) in its message,
# leave no output and no temporary file, and leave every input byte-for-byte as it was.
# Run by CTest (label bad_input) with CDEM (the binary) and SRC (the source tree) set; needs
# /usr/bin/python3 with h5py to corrupt specimen files.
set -u
: "${CDEM:?}" "${SRC:?}"
PY=${PYTHON_H5PY:-/usr/bin/python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
passed=0

# A tiny specimen (20 x 20 mm, 2.5-5 mm aggregates) and a uniaxial test on it: a run takes a
# fraction of a second.
cp "$SRC/tests/tiny_specimen.toml" spec.toml
cp "$SRC/samples/c30_materials.toml" materials.toml
"$CDEM" generate spec.toml -o specimen.h5 -q || { echo "FAIL: cannot generate the specimen"; exit 1; }
test_file() { printf 'seed = 1\nspecimen = "%s"\nmaterials = "materials.toml"\n[test]\ntype = "uniaxial"\nmax_steps = 20000\n' "$1"; }
test_file specimen.h5 > test.toml
printf 'a regular file\n' > somefile
mkfifo fifo
mkdir adir
ln -s specimen.h5 link_to_specimen.h5
ln -s nowhere.h5 dangling.h5
ln specimen.h5 hardlink_to_specimen.h5
ln -s . here

inputs="spec.toml specimen.h5 test.toml materials.toml somefile"
checksum() { md5sum $inputs 2>/dev/null; }
before=$(checksum)

# expect NAME CODE "FILE_PATTERN" "KEY_PATTERN" "OUTPUTS" -- COMMAND...: run the command, then
# check the exit code, that the message holds both patterns, that none of OUTPUTS exists, that no
# temporary file (NAME.tmpPID) is left anywhere in the work folder, and that the inputs are intact.
expect() {
  local name=$1 code=$2 file_pattern=$3 key_pattern=$4 outputs=$5
  shift 6
  timeout 120 "$@" >/dev/null 2>"$name.err"
  local rc=$?
  local fail=""
  [ "$rc" -eq "$code" ] || fail="exit $rc, expected $code"
  [ -z "$fail" ] && ! grep -qF -- "$file_pattern" "$name.err" && fail="message lacks the file '$file_pattern'"
  [ -z "$fail" ] && ! grep -qF -- "$key_pattern" "$name.err" && fail="message lacks the key '$key_pattern'"
  for o in $outputs; do
    [ -z "$fail" ] && [ -e "$o" ] && fail="left the output $o"
  done
  local temps
  temps=$(find . -name '*.tmp[0-9]*' | head -3)
  [ -z "$fail" ] && [ -n "$temps" ] && fail="left temporary files: $temps"
  [ -z "$fail" ] && [ "$(checksum)" != "$before" ] && fail="changed an input"
  if [ -n "$fail" ]; then
    echo "FAIL $name: $fail"; cat "$name.err"; failures=$((failures + 1))
  else
    echo "ok   $name: $(head -c 240 "$name.err" | tr '\n' ' ')"; passed=$((passed + 1))
  fi
}

# --- cdem generate: outputs --------------------------------------------------------------------
G=("$CDEM" generate spec.toml -q)
expect gen_summary_is_output 2 "g1.h5" "--summary" "g1.h5" -- "${G[@]}" -o g1.h5 --summary g1.h5
expect gen_picture_is_output 2 "g2.h5" "--picture" "g2.h5" -- "${G[@]}" -o g2.h5 --picture g2.h5
expect gen_picture_is_summary 2 "g3.json" "--picture" "g3.h5 g3.json" -- \
  "${G[@]}" -o g3.h5 --summary g3.json --picture g3.json
expect gen_output_is_spec 2 "spec.toml" "-o" "" -- "${G[@]}" -o spec.toml
expect gen_output_is_spec_respelt 2 "adir/../spec.toml" "-o" "" -- "${G[@]}" -o adir/../spec.toml
expect gen_output_is_spec_via_dir_link 2 "here/spec.toml" "-o" "" -- "${G[@]}" -o here/spec.toml
expect gen_output_fifo 2 "fifo" "FIFO" "" -- "${G[@]}" -o fifo
expect gen_output_symlink 2 "link_to_specimen.h5" "symbolic link" "" -- "${G[@]}" -o link_to_specimen.h5
expect gen_output_dangling_symlink 2 "dangling.h5" "symbolic link" "nowhere.h5" -- \
  "${G[@]}" -o dangling.h5
expect gen_output_directory 2 "adir" "directory" "" -- "${G[@]}" -o adir
expect gen_output_under_a_file 2 "somefile/out.h5" "not a directory" "" -- \
  "${G[@]}" -o somefile/out.h5
expect gen_summary_under_a_file 2 "somefile/s.json" "--summary" "g4.h5" -- \
  "${G[@]}" -o g4.h5 --summary somefile/s.json
expect gen_picture_fifo 2 "fifo" "--picture" "g5.h5" -- "${G[@]}" -o g5.h5 --picture fifo
expect gen_summary_is_spec 2 "spec.toml" "--summary" "g6.h5" -- "${G[@]}" -o g6.h5 --summary spec.toml

# --- cdem generate: bad values in the generator file ----------------------------------------------
variant() { sed -e "$2" spec.toml > "$1.toml"; }
variant nan_width 's/^width_mm = 20/width_mm = nan/'
expect gen_nan_width 2 "nan_width.toml" "specimen.width_mm" "g7.h5" -- \
  "$CDEM" generate nan_width.toml -o g7.h5 -q
variant inf_radius 's/^r_mean_mm = 0.5/r_mean_mm = inf/'
expect gen_inf_radius 2 "inf_radius.toml" "mortar.r_mean_mm" "g8.h5" -- \
  "$CDEM" generate inf_radius.toml -o g8.h5 -q

# --- cdem run: outputs -------------------------------------------------------------------------
R=("$CDEM" run test.toml -q)
expect run_output_is_specimen 2 "specimen.h5" "-o" "specimen.xmf specimen_cracks.png" -- "${R[@]}" -o specimen.h5
expect run_output_is_specimen_hardlink 2 "hardlink_to_specimen.h5" "-o" "" -- \
  "${R[@]}" -o hardlink_to_specimen.h5
expect run_output_is_specimen_via_dir_link 2 "here/specimen.h5" "-o" "" -- "${R[@]}" -o here/specimen.h5
expect run_output_is_test 2 "test.toml" "-o" "test.xmf" -- "${R[@]}" -o test.toml
expect run_output_is_materials 2 "materials.toml" "-o" "" -- "${R[@]}" -o materials.toml
expect run_summary_is_output 2 "r1.h5" "--summary" "r1.h5 r1.xmf" -- "${R[@]}" -o r1.h5 --summary r1.h5
expect run_summary_is_test 2 "test.toml" "--summary" "r2.h5" -- "${R[@]}" -o r2.h5 --summary test.toml
expect run_output_is_its_xdmf 2 "r3.xmf" "XDMF" "" -- "${R[@]}" -o r3.xmf
expect run_summary_is_its_bonds_xdmf 2 "r8_bonds.xmf" "bonds XDMF" "r8.h5 r8.xmf r8_cracks.xmf" -- \
  "${R[@]}" -o r8.h5 --summary r8_bonds.xmf
expect run_plot_is_summary 2 "r4.json" "--plot" "r4.h5 r4.json" -- \
  "${R[@]}" -o r4.h5 --summary r4.json --plot r4.json
expect run_crack_map_is_plot 2 "r5.png" "--crack-map" "r5.h5" -- \
  "${R[@]}" -o r5.h5 --plot r5.png --crack-map r5.png
expect run_output_under_a_file 2 "somefile/out.h5" "not a directory" "" -- "${R[@]}" -o somefile/out.h5
expect run_summary_under_a_file 2 "somefile/s.json" "--summary" "r6.h5 r6.xmf r6_cracks.png" -- \
  "${R[@]}" -o r6.h5 --summary somefile/s.json
expect run_output_fifo 2 "fifo" "FIFO" "" -- "${R[@]}" -o fifo
expect run_output_symlink 2 "link_to_specimen.h5" "symbolic link" "" -- "${R[@]}" -o link_to_specimen.h5
expect run_crack_map_directory 2 "adir" "--crack-map" "r7.h5" -- "${R[@]}" -o r7.h5 --crack-map adir
expect run_summary_fifo 2 "fifo" "--summary" "r8.h5" -- "${R[@]}" -o r8.h5 --summary fifo

# A biaxial series writes one picture per confinement, "_cK" before the extension: those names
# are outputs too.
printf 'seed = 1\nspecimen = "specimen.h5"\nmaterials = "materials.toml"\n[test]\ntype = "biaxial"\nconfining_stresses_MPa = [0.5, 2]\n' > biaxial.toml
expect run_biaxial_picture_is_summary 2 "bx_c1.png" "--plot" "bx.h5 bx_c1.png" -- \
  "$CDEM" run biaxial.toml -o bx.h5 --plot bx.png --summary bx_c1.png -q

# --- cdem run: corrupt specimen files (values set with h5py) --------------------------------------
# corrupt NAME DATASET INDEX VALUE: a copy of the specimen with one value replaced, and its test.
corrupt() {
  cp specimen.h5 "$1.h5"
  "$PY" - "$1.h5" "$2" "$3" "$4" <<'PY'
import sys, h5py
path, dataset, index, value = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
with h5py.File(path, "r+") as f:
    if index < 0:
        obj, name = dataset.rsplit("/", 1) if "/" in dataset else ("/", dataset)
        f[obj].attrs[name] = value
    else:
        d = f[dataset]
        if d.ndim == 2:
            d[index, 0] = value
        else:
            d[index] = value
PY
  test_file "$1.h5" > "$1.toml"
}
# bad_specimen NAME DATASET INDEX VALUE: the run must be refused naming the file and dataset.
bad_specimen() {
  corrupt "$1" "$2" "$3" "$4"
  expect "specimen_$1" 2 "$1.h5" "$2" "$1_out.h5 $1_out.json" -- \
    "$CDEM" run "$1.toml" -o "$1_out.h5" --summary "$1_out.json" -q
}
bad_specimen nan_radius discs/r 3 nan
bad_specimen inf_x discs/x 4 inf
bad_specimen nan_y discs/y 5 nan
bad_specimen negative_radius discs/r 6 -0.001
bad_specimen zero_radius discs/r 7 0
bad_specimen disc_5m_outside discs/x 8 5.0
bad_specimen x_1p5e307 discs/x 9 1.5e307
bad_specimen y_below_mould discs/y 10 -0.5
bad_specimen contact_active_7 discs/contact_active 11 7
bad_specimen clump_out_of_range discs/clump 12 99999
bad_specimen negative_clump_mass clumps/mass 0 -1
bad_specimen nan_clump_inertia clumps/inertia 0 nan
bad_specimen nan_centroid clumps/centroid 0 nan
bad_specimen inf_vertex clumps/vertices 0 inf
bad_specimen negative_mould_width container/width_m -1 -0.02
bad_specimen nan_mortar_density mortar_density_kg_m3 -1 nan
# A dataset removed, and a file cut short.
cp specimen.h5 no_radius.h5
"$PY" -c 'import h5py,sys; f=h5py.File(sys.argv[1],"r+"); del f["discs/r"]' no_radius.h5
test_file no_radius.h5 > no_radius.toml
expect specimen_missing_radius 2 "no_radius.h5" "discs/r" "nr.h5" -- "$CDEM" run no_radius.toml -o nr.h5 -q
head -c 3000 specimen.h5 > cut.h5
test_file cut.h5 > cut.toml
expect specimen_cut_short 2 "cut.h5" "HDF5" "cut_out.h5" -- "$CDEM" run cut.toml -o cut_out.h5 -q

# --- write errors: the file-size limit (ulimit -f, in KiB) cuts the writes short -------------------
# (tests run as root, where permission bits do not stop a write; a size limit does.)
limited=(bash -c 'ulimit -f 8; exec "$@"' limited)
expect write_error_generate 3 "fs.h5" "File too large" "fs.h5 fs.json fs.png" -- \
  "${limited[@]}" "$CDEM" generate spec.toml -o fs.h5 --summary fs.json --picture fs.png -q
printf 'seed = 1\nspecimen = "specimen.h5"\nmaterials = "materials.toml"\n[test]\ntype = "uniaxial"\nmax_steps = 20000\nsnapshot_interval = 500\n' > snapshots.toml
expect write_error_run 3 "fs_run.h5" "File too large" "fs_run.h5 fs_run.xmf fs_run.json fs_run_cracks.png" -- \
  "${limited[@]}" "$CDEM" run snapshots.toml -o fs_run.h5 --summary fs_run.json -q

# --- cdem campaign: checked before any run -------------------------------------------------------
campaign() {  # campaign NAME COMMAND BASE GATHER FACTOR_TABLE
  cat > "$1.toml" <<TOML
base = "$3"
output_dir = "$1_out"
gather = [$4]
[job]
command = "$2"
args = ["{input}", "-o", "{dir}/out.h5", "--summary", "{summary}", "-q"]
[design]
type = "full_factorial"
[[factors]]
$5
TOML
}
campaign level_out_of_range generate spec.toml '"discs"' 'key = "mortar.porosity"
values = [0.12, 1.5]'
expect campaign_level_out_of_range 2 "level_out_of_range.toml" "mortar.porosity" "level_out_of_range_out" -- \
  "$CDEM" campaign level_out_of_range.toml -q
campaign negative_level generate spec.toml '"discs"' 'key = "gradation.p_k"
values = [-0.5, 0.5]'
expect campaign_negative_level 2 "negative_level.toml" "gradation.p_k" "negative_level_out" -- \
  "$CDEM" campaign negative_level.toml -q
campaign command_rm rm spec.toml '"discs"' 'key = "mortar.porosity"
values = [0.1, 0.12]'
expect campaign_unknown_command 2 "command_rm.toml" "job.command" "command_rm_out" -- \
  "$CDEM" campaign command_rm.toml -q
campaign misspelt_gather generate spec.toml '"porosty"' 'key = "mortar.porosity"
values = [0.1, 0.12]'
expect campaign_misspelt_gather 2 "misspelt_gather.toml" "porosty" "misspelt_gather_out" -- \
  "$CDEM" campaign misspelt_gather.toml -q
# A run's input is written to its run directory, so a base run input names its files by absolute
# path (a relative one is refused before any run: it would not resolve from runs/NNNN/).
printf 'seed = 1\nspecimen = "%s"\nmaterials = "%s"\n[test]\ntype = "uniaxial"\nplaten_velocity_m_s = 0.02\nmax_steps = 20000\n' \
  "$work/specimen.h5" "$work/materials.toml" > run_base.toml
campaign run_relative_specimen run test.toml '"peak_stress_MPa"' 'key = "test.max_steps"
values = [10000, 20000]'
expect campaign_run_relative_specimen 2 "run_relative_specimen.toml" "specimen" \
  "run_relative_specimen_out" -- "$CDEM" campaign run_relative_specimen.toml -q
campaign run_misspelt_gather run run_base.toml '"peak_stres_MPa"' 'key = "test.max_steps"
values = [10000, 20000]'
expect campaign_run_misspelt_gather 2 "run_misspelt_gather.toml" "peak_stres_MPa" \
  "run_misspelt_gather_out" -- "$CDEM" campaign run_misspelt_gather.toml -q
campaign run_negative_velocity run run_base.toml '"peak_stress_MPa"' 'key = "test.platen_velocity_m_s"
values = [-0.02, 0.02]'
expect campaign_run_negative_velocity 2 "run_negative_velocity.toml" "test.platen_velocity" \
  "run_negative_velocity_out" -- "$CDEM" campaign run_negative_velocity.toml -q
campaign output_is_file generate spec.toml '"discs"' 'key = "mortar.porosity"
values = [0.1, 0.12]'
expect campaign_output_is_a_file 2 "somefile" "-o" "" -- "$CDEM" campaign output_is_file.toml -o somefile -q

# Controls: gathering every field of a real summary passes the check and the campaign runs, so
# the checks above refuse the misspelt fields, not everything.
leaf_paths() {
  "$PY" - "$1" <<'PY'
import json, sys
def walk(node, path):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from walk(v, path + [k])
    elif isinstance(node, list) and node and isinstance(node[0], (dict, list)):
        yield from walk(node[0], path + ["0"])
    else:
        yield ".".join(path)
print(", ".join(json.dumps(p) for p in walk(json.load(open(sys.argv[1])), [])))
PY
}
control() {  # control NAME: the campaign must run and every gathered column must be filled
  timeout 120 "$CDEM" campaign "$1.toml" -j 2 -q >/dev/null 2>"$1.err"
  local rc=$? empty
  empty=$("$PY" -c 'import csv,sys; rows=list(csv.DictReader(open(sys.argv[1])));
print(sum(1 for r in rows for k, v in r.items() if v == "" and k != "message"))' \
    "$1_out/results.csv" 2>/dev/null)
  if [ "$rc" -ne 0 ] || [ "${empty:-x}" != 0 ]; then
    echo "FAIL control $1: exit $rc, empty cells ${empty:-none read}"; cat "$1.err"
    failures=$((failures + 1))
  else
    echo "ok   control $1: every summary field gathered, none empty"; passed=$((passed + 1))
  fi
}
"$CDEM" generate spec.toml -o control.h5 --summary control_generate.json -q
campaign all_generate_fields generate spec.toml "$(leaf_paths control_generate.json)" 'key = "mortar.porosity"
values = [0.11, 0.12]'
control all_generate_fields
"$CDEM" run run_base.toml --summary control_run.json -q
campaign all_run_fields run run_base.toml "$(leaf_paths control_run.json)" 'key = "test.max_steps"
values = [20000, 30000]'
control all_run_fields

# --- cdem calibrate: the generator file checked before any job -----------------------------------
cp "$SRC/samples/c30_calibrate.toml" "$SRC/samples/c30_calibrate_ucs.toml" \
  "$SRC/samples/c30_calibrate_specimen.toml" "$SRC/samples/c30_materials.toml" .
sed -e 's/^width_mm = .*/width_mm = -40/' c30_calibrate_specimen.toml > bad_generator.toml
sed -e 's/c30_calibrate_specimen.toml/bad_generator.toml/' c30_calibrate.toml > cal_bad_generator.toml
expect calibrate_bad_generator 2 "bad_generator.toml" "specimen.width_mm" "cal_out" -- \
  "$CDEM" calibrate cal_bad_generator.toml -o cal_out -q
expect calibrate_output_is_input 2 "c30_calibrate.toml" "-o" "" -- \
  "$CDEM" calibrate c30_calibrate.toml -o c30_calibrate.toml -q

# --- cdem calibrate with a G_F target (three-point bending): the bending test and its notched
# beams must be named, of the right type, and a sound beam; fast cannot set sigma_t and G_F apart.
mkdir -p materials
cp "$SRC/samples/c30_calibrate_gf.toml" "$SRC/samples/small_beam_bending.toml" \
  "$SRC/samples/small_beam_specimen.toml" "$SRC/samples/c30_flat_joint_calibrate_tension.toml" .
cp "$SRC/samples/materials/c30_flat_joint.toml" "$SRC/samples/materials/c30_flat_joint_start.toml" \
  materials/
grep -v '^bending = ' c30_calibrate_gf.toml > cal_gf_no_test.toml
expect calibrate_gf_without_bending_test 2 "cal_gf_no_test.toml" "tests.bending" "cal_out" -- \
  "$CDEM" calibrate cal_gf_no_test.toml -o cal_out -q
grep -v '^bending_generator = ' c30_calibrate_gf.toml > cal_gf_no_generator.toml
expect calibrate_gf_without_beam_generator 2 "cal_gf_no_generator.toml" \
  "specimen.bending_generator" "cal_out" -- "$CDEM" calibrate cal_gf_no_generator.toml -o cal_out -q
sed -e 's/^bending = .*/bending = "c30_calibrate_ucs.toml"/' c30_calibrate_gf.toml > cal_gf_wrong_test.toml
expect calibrate_gf_test_not_bending 2 "c30_calibrate_ucs.toml" "tests.bending" "cal_out" -- \
  "$CDEM" calibrate cal_gf_wrong_test.toml -o cal_out -q
sed -e 's/^G_F_N_per_m = .*/G_F_N_per_m = -20/' c30_calibrate_gf.toml > cal_gf_negative.toml
expect calibrate_gf_negative 2 "cal_gf_negative.toml" "targets.G_F_N_per_m" "cal_out" -- \
  "$CDEM" calibrate cal_gf_negative.toml -o cal_out -q
sed -e 's/^notch_depth_mm = .*/notch_depth_mm = 15/' small_beam_specimen.toml > deep_notch.toml
sed -e 's/small_beam_specimen.toml/deep_notch.toml/' c30_calibrate_gf.toml > cal_gf_deep_notch.toml
expect calibrate_gf_notch_too_deep 2 "deep_notch.toml" "specimen.notch_depth" "cal_out" -- \
  "$CDEM" calibrate cal_gf_deep_notch.toml -o cal_out -q
sed -e 's/^G_F_N_per_m = .*/&\nsigma_t_MPa = 2.9/' \
  -e 's/^bending = .*/&\ndirect_tension = "c30_flat_joint_calibrate_tension.toml"/' \
  -e 's/^bending_generator = .*/&\ngenerator = "small_beam_specimen.toml"/' \
  c30_calibrate_gf.toml > cal_gf_sigma_t.toml
expect calibrate_gf_with_sigma_t_fast 2 "cal_gf_sigma_t.toml" "targets" "cal_out" -- \
  "$CDEM" calibrate cal_gf_sigma_t.toml -o cal_out -q

# --- cdem calibrate strategy "tables" (issue 17): what the lookup tables do not hold --------------
mkdir -p tables_case/samples tables_case/tables
cp -r "$SRC/samples/sandstone" tables_case/samples/
cp "$SRC/samples/sandstone_calibrate_r2.7.toml" tables_case/samples/cal.toml
cp "$SRC/tables/brazilian_kb_x_table.csv" "$SRC/tables/uniaxial_ke_table.csv" tables_case/tables/
tcal() { sed -e "$2" tables_case/samples/cal.toml > "tables_case/samples/$1.toml"; }
tcal tables_target 's/^sigma_t_MPa = .*/sigma_t_MPa = 90/'
expect calibrate_tables_target_outside 2 "tables_target.toml" "targets.sigma_t" "cal_out" -- \
  "$CDEM" calibrate tables_case/samples/tables_target.toml -o cal_out -q
sed -e 's/^r_ratio = .*/r_ratio = 6.0/' tables_case/samples/sandstone/disc_r2.7.toml \
  > tables_case/samples/sandstone/disc_wide.toml
tcal tables_packing 's/disc_r2.7.toml/disc_wide.toml/'
expect calibrate_tables_packing_outside 2 "tables_packing.toml" "specimen.brazilian_generator" \
  "cal_out" -- "$CDEM" calibrate tables_case/samples/tables_packing.toml -o cal_out -q
tcal tables_missing 's#brazilian_kb_x_table.csv#nowhere.csv#'
expect calibrate_tables_missing 2 "nowhere.csv" "tables.kb" "cal_out" -- \
  "$CDEM" calibrate tables_case/samples/tables_missing.toml -o cal_out -q
sed -e 's/^r_ratio,r_min_mm,emod_per_sigma_cn,K_B/r_ratio,r_min_mm,emod_per_sigma_cn,K/' \
  tables_case/tables/brazilian_kb_x_table.csv > tables_case/tables/corrupt.csv
tcal tables_corrupt 's#brazilian_kb_x_table.csv#corrupt.csv#'
expect calibrate_tables_corrupt 2 "corrupt.csv" "tables.kb" "cal_out" -- \
  "$CDEM" calibrate tables_case/samples/tables_corrupt.toml -o cal_out -q
sed -e 's/^kratio = .*/kratio = 3.0/' tables_case/samples/sandstone/materials.toml \
  > tables_case/samples/sandstone/materials_k3.toml
sed -e 's/materials.toml/materials_k3.toml/' tables_case/samples/sandstone/ucs.toml \
  > tables_case/samples/sandstone/ucs_k3.toml
tcal tables_kratio 's#sandstone/ucs.toml#sandstone/ucs_k3.toml#'
expect calibrate_tables_kratio 2 "tables_kratio.toml" "materials.mortar.kratio" "cal_out" -- \
  "$CDEM" calibrate tables_case/samples/tables_kratio.toml -o cal_out -q
# texpect NAME KEY SED: the sample edited by SED refused (exit 2) naming NAME.toml and KEY.
texpect() {
  tcal "$1" "$3"
  expect "calibrate_$1" 2 "$1.toml" "$2" "cal_out" -- \
    "$CDEM" calibrate "tables_case/samples/$1.toml" -o cal_out -q
}
# nu (its kn/ks key free) beside sigma_t: the strength tables hold one kn/ks, and how they move
# with it is the kn/ks factor table's (tables.kratio) to say: missing; and a nu that needs a
# kn/ks below the factors' 1.5 (nu 0.17 on cell 2.7: kn/ks about 1.2).
texpect tables_nu tables.kratio 's/^E_GPa = 18/&\nnu = 0.2/
$a [[parameters]]\nkey = "materials.mortar.kratio"\nbounds = [0.8, 6]'
cp "$SRC/tables/uniaxial_nu_table.csv" "$SRC/tables/kratio_factors.csv" tables_case/tables/
texpect tables_nu_kratio_outside "targets.nu': nu = 0.17 needs kn/ks" 's/^E_GPa = 18/&\nnu = 0.17/
s#^ke = .*#\nnu = "../tables/uniaxial_nu_table.csv"\nkratio = "../tables/kratio_factors.csv"#
$a [[parameters]]\nkey = "materials.mortar.kratio"\nbounds = [0.8, 6]'
cp "$SRC/tables/uniaxial_ku_table.csv" tables_case/tables/
texpect tables_ucs_outside targets.sigma_u \
  's/^E_GPa = 18/&\nsigma_u_MPa = 200/; s#^ke = .*#&\nku = "../tables/uniaxial_ku_table.csv"#'
texpect tables_no_ku tables.ku 's/^E_GPa = 18/&\nsigma_u_MPa = 40/'
# The K_B table against tau_cs / sigma_cn (kb_tau): missing, and a sigma_u that the three tables
# solved together cannot reach with sigma_t 9.08 MPa.
cp "$SRC/tables/brazilian_kb_tau_table.csv" tables_case/tables/
texpect tables_kb_tau_missing tables.kb_tau \
  's/^E_GPa = 18/&\nsigma_u_MPa = 45.4/; s#^ke = .*#&\nku = "../tables/uniaxial_ku_table.csv"\nkb_tau = "../tables/nowhere.csv"#'
texpect tables_coupled_outside targets.sigma_u \
  's/^E_GPa = 18/&\nsigma_u_MPa = 200/; s#^ke = .*#&\nku = "../tables/uniaxial_ku_table.csv"\nkb_tau = "../tables/brazilian_kb_tau_table.csv"#'
# The jaws' K_B table with a Brazilian test loaded through loading arcs (session 13).
texpect tables_loading tests.brazilian 's#sandstone/brazilian.toml#sandstone/brazilian_arc.toml#'
# A uniaxial rectangle of another size than the K_E table's 20 x 40 mm (session 14).
sed -e 's/^width_mm = .*/width_mm = 30/; s/^height_mm = .*/height_mm = 60/' \
  tables_case/samples/sandstone/rectangle_r2.7.toml > tables_case/samples/sandstone/rect_30x60.toml
texpect tables_ke_size specimen.generator 's#sandstone/rectangle_r2.7.toml#sandstone/rect_30x60.toml#'
# A friction-angle target (session 15) beyond the Mohr-Coulomb table (and c without phi).
cp "$SRC/tables/biaxial_mc_rho2_table.csv" tables_case/tables/
texpect tables_phi_outside targets.phi_deg \
  's/^E_GPa = 18/&\nphi_deg = 80/; s#^ke = .*#&\nmc = "../tables/biaxial_mc_rho2_table.csv"#'
texpect tables_c_without_phi targets.c 's/^E_GPa = 18/&\nc_MPa = 10/'
# sigma_t 9.08 MPa by direct tension (session 18): below what K_D reaches at E 18 GPa on cell 2.7
# (9.64 to 19.33 MPa: E* / sigma_cn would pass the table's 1,200); and the K_D table not named.
cp "$SRC/samples/sandstone/direct_tension.toml" tables_case/samples/sandstone/
cp "$SRC/tables/direct_tension_kd_cells_levels.csv" tables_case/tables/
texpect tables_dt_outside targets.sigma_t \
  's#^brazilian = .*#direct_tension = "sandstone/direct_tension.toml"#; s#^kb = .*#kd = "../tables/direct_tension_kd_cells_levels.csv"#'
texpect tables_dt_no_kd tables.kd 's#^brazilian = .*#direct_tension = "sandstone/direct_tension.toml"#'

echo "$passed passed, $failures failed"
[ "$passed" -ge 40 ] || { echo "FAIL: fewer than 40 cases ran"; exit 1; }
[ "$failures" -eq 0 ]
