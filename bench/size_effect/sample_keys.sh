# Helpers of the bench scripts that run the samples with some keys changed, sourced by
# bench/size_effect/size_effect.sh and bench/bending_tail/material_resolution.sh after they set
# `script` (their path, for the marks and messages) and `src` (the repository).

# enter_output BUILD_DIR OUT_DIR: the build and output directories as absolute paths (`build`,
# `out`; OUT_DIR made if missing), `cdem` the binary, and cd into OUT_DIR.
enter_output() {
  build="$(cd "$1" && pwd)"
  mkdir -p "$2"
  out="$(cd "$2" && pwd)"
  cdem="$build/bin/cdem"
  cd "$out"
}

# set_key FILE KEY VALUE: replace the value of a key of a copied sample and mark it; a key the
# file does not hold is an error (exit 2), not a silent no-op.
set_key() {
  sed -i -E "s|^$2 = .*|$2 = $3  # set by $script|" "$1"
  grep -q "^$2 = $3 " "$1" || { echo "$script: no key $2 in $1" >&2; exit 2; }
}

# copy_material: (in OUT_DIR) the calibrated flat-joint C30 as materials.toml, left untouched when the same
# (a resumed call keeps the file its earlier runs named).
copy_material() {
  cmp -s "$src/samples/materials/c30_flat_joint.toml" materials.toml ||
    cp "$src/samples/materials/c30_flat_joint.toml" materials.toml
}
