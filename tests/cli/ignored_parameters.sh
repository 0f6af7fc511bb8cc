# A parameter set in the file or by --set that the scene does not use gets one
# warning line naming it and why: Young's modulus while every particle is the
# preset Sn (set in the file), die friction with the die off (set by --set;
# the die's diameter, set in the file, is then unused too).
# Every scene in prm/ sets only what it uses; a used entry gives no warning.
set -eu
cd "$WORK_DIR"
light="$SOURCE_DIR/prm/single_layer_sn_light.prm"
seven="$SOURCE_DIR/prm/seven_spheres_sn.prm"

expect_warnings() {  # expected count, then the densify arguments
  n=$1; shift
  "$DENSIFY" --validate "$@" > out.txt 2> err.txt || { cat err.txt; echo "FAIL: exit code" >&2; exit 1; }
  cat err.txt
  [ "$(grep -c '^densify: warning: ' err.txt || true)" -eq "$n" ] \
    || { echo "FAIL: expected $n warning(s)" >&2; exit 1; }
  [ "$(wc -l < err.txt)" -eq "$n" ] || { echo "FAIL: other output on stderr" >&2; exit 1; }
  grep -q ": valid (" out.txt
}

echo "== Young's modulus in the file, the particles are Sn"
{ cat "$light"; printf 'subsection Material\n  set Young'"'"'s modulus = 50000  # a comment\nend\n'; } > young.prm
expect_warnings 1 young.prm
grep -q "^densify: warning: Material/Young's modulus = 50000 has no effect: only the material 'custom' uses it, and no particle is 'custom' (Particles/Materials = Sn" err.txt

echo "== the same for the material custom: used, no warning"
expect_warnings 0 young.prm --set "Particles/Materials=custom"

echo "== die friction by --set, the die off (its diameter, set in the file, then too)"
expect_warnings 2 "$seven" --set "Tools/Die wall/Enabled=false" \
  --set " Tools / Die wall / Friction coefficient = 0.3"
grep -q "^densify: warning: Tools/Die wall/Friction coefficient = 0.3 has no effect: the die wall is off" err.txt
grep -q "^densify: warning: Tools/Die wall/Diameter = 7.52 has no effect: the die wall is off" err.txt

echo "== the same with the die on: no warning"
expect_warnings 0 "$seven" --set "Tools/Die wall/Friction coefficient=0.3"

echo "== every scene in prm/: no warning"
for scene in "$SOURCE_DIR"/prm/*.prm; do
  expect_warnings 0 "$scene"
done
echo "ignored_parameters: all checks passed"
