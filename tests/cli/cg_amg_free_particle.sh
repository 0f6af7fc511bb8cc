# CG with ML AMG on a scene with a free particle: three tin spheres in a row
# pressed by the punches and a fourth, small sphere that touches nothing
# (friction 0.2, 0.6 mm mesh, 3 steps, each solver with the friction tangent
# auto takes: secant-start with the direct solver, symmetric-secant-start
# with CG, which follow the same Newton path to the same state). The AMG
# set-up and CG handle the particle that no contact holds (the
# stabilisation holds it): on 1 and 2 ranks the run finishes, within a time
# limit (no hang), with the direct solver's forces
# (tests/cli/lib/solver_agree.bash), and the free sphere does not move.
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/solver_agree.bash"
solvers_agree "$SOURCE_DIR/prm/seven_spheres_sn.prm" \
  --set "Particles/Centres=-2.5,0,1.25; 0,0,1.25; 2.5,0,1.25; 5,0,1.25" \
  --set "Particles/Diameters=2.5,2.5,2.5,1.0" \
  --set "Tools/Die wall/Diameter=12" --set "Mesh/Element size=0.6" \
  --set "Time stepping/Number of steps=3" --set "Time stepping/End time=0.3" \
  --set "Tools/Upper punch/Displacement history=0:0, 0.3:0.09" \
  --set "Output/Interval=0" --set "Output/Checkpoint interval=0"
grep -q "4 particle(s)" amg2.log
# particles.csv: particle 3's mean displacement (columns 6-8) stays below
# 1e-9 mm at every step
for run in amg1 amg2; do
  awk -F, '$2 == 3 {n++; for (c = 6; c <= 8; ++c) if ($c > 1e-9 || $c < -1e-9) bad++}
    END {printf "%s: free particle at %d steps, moved at %d\n", FILENAME, n, bad
      exit !(n == 3 && bad == 0)}' "$run/particles.csv"
done
