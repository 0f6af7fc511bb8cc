# Hard case: a large load step. An elastic sphere (prm/single_sphere_sn.prm,
# P1, 0.6 mm mesh, 0.2 at the poles, poles held on the axis) flattened by
# 10 % (0.25 mm) between frictionless punches in one step converges without
# a cut-back and ends at the force of 8 steps: without friction or
# plasticity the answer does not depend on the path. Measured: 4751.18 N in
# 18 Newton iterations (one step) against 4751.01 N in 64 (8 steps). The
# tolerance 1e-4 is that of the contact's augmented Lagrangian, which stops
# at a penetration below Contact/Gap tolerance (1e-4 mm), not at zero.
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/hard_case.bash"
sphere=(--set "Output/Interval=0" --set "Material/Model=elastic"
  --set "Mesh/Polynomial degree=1" --set "Mesh/Element size=0.6"
  --set "Mesh/Refined element size=0.2"
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.25")
"$DENSIFY" "$SOURCE_DIR/prm/single_sphere_sn.prm" "${sphere[@]}" \
  --set "Time stepping/Number of steps=8" --set "Output/Directory=eight" \
  > eight.log 2>&1
check_run eight 8 4751.01 1e-4
reference=$(tail -n 1 eight/statistics.csv | cut -d, -f4)
"$DENSIFY" "$SOURCE_DIR/prm/single_sphere_sn.prm" "${sphere[@]}" \
  --set "Time stepping/Number of steps=1" --set "Output/Directory=one" \
  > one.log 2>&1
check_run one 1 "$reference" 1e-4
cutbacks=$(tail -n 1 one/statistics.csv | cut -d, -f18)
echo "cut-backs of the single step: $cutbacks"
[ "$fails" -eq 0 ] && [ "$cutbacks" = 0 ]
