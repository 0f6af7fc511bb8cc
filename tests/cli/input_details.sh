# Details of bad input: each is refused with exit code 2 and one line naming
# the entry (or read as meant), before any meshing.
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
prm="$SOURCE_DIR/prm/default.prm"
layer="$SOURCE_DIR/prm/single_layer_sn_light.prm"
run=("$DENSIFY" "$prm" --set "Output/Directory=out")

# a negative or NaN diameter is a diameter error, also where the punch would
# start below the lower punch
expect_error "negative diameter" 2 "diameter -3 mm must be a number > 0" \
  "${run[@]}" --set "Particles/Diameters=-3"
expect_error "NaN diameter" 2 "Particles/Diameters" \
  "${run[@]}" --set "Particles/Diameters=nan"
# Young's modulus in Pa instead of MPa
expect_error "Young's modulus 1e300" 2 "Material/Young's modulus" \
  "${run[@]}" --set "Particles/Materials=custom" --set "Material/Young's modulus=1e300"
# a hexagonal layer has one material
expect_error "materials list with a layer" 2 "Particles/Materials" \
  "$DENSIFY" "$layer" --set "Output/Directory=out" --set "Particles/Materials=Sn, Fe"
# a misspelt subsection is blamed, not the entry
expect_error "misspelt subsection" 2 "no subsection 'Particle'" \
  "${run[@]}" --set "Particle/Diameters=2"
expect_error "misspelt nested subsection" 2 "no subsection 'Tools/Upper punsh'" \
  "${run[@]}" --set "Tools/Upper punsh/Enabled=true"
# a zero refinement direction is bad input (exit 2), found before meshing
expect_error "zero refinement direction" 2 "Mesh/Refinement directions" \
  "${run[@]}" --set "Mesh/Refinement directions=0,0,0"

# a UTF-8 byte-order mark before the first line
printf '\xef\xbb\xbfsubsection Particles\n  set Centres = 0,0,1.25\nend\n' > bom.prm
out=$("$DENSIFY" --validate bom.prm 2>&1)
rc=$?
if [ $rc -ne 0 ] || printf '%s' "$out" | grep -q "densify: "; then
  echo "FAIL byte-order mark: exit $rc: $out"
  fails=$((fails + 1))
else
  echo "ok   byte-order mark: $out"
fi
[ ! -e out ] || { echo "FAIL: a refused run created its output directory"; fails=$((fails + 1)); }
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
