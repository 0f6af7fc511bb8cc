# Bad input gives one clear error line naming the parameter, exit code 2, no crash or hang.
# (its one 2-rank run stops at the input check: one processor's work)
# ctest processors: 1
set -u
cd "$WORK_DIR"
fails=0
cat > good.prm <<'PRM'
subsection Particles
  set Centres = 0,0,1.25
end
subsection Output
  set Directory = out
end
PRM
sed 's/set Centres/set Centers/' good.prm > misspelt.prm

# expect NAME PATTERN ARGS...: exit code 2 and exactly one line matching PATTERN
expect() {
  local name=$1 pattern=$2
  shift 2
  local out rc
  out=$(timeout 60 "$@" 2>&1)
  rc=$?
  # mpirun adds its own banner: count only our lines there; warnings about
  # entries without effect (a base file's Centres under a particle file) are
  # not errors
  local ours
  ours=$(printf '%s\n' "$out" | grep -v -e '^---' -e '^mpirun' -e '^Primary job' \
    -e '^densify: warning: ' \
    -e '^a non-zero' -e '^the job' -e '^  Process name' -e '^  Exit code' \
    -e '^$' -e 'returned$' -e 'job has been aborted' | wc -l)
  if [ $rc -ne 2 ] || [ "$ours" -ne 1 ] ||
    ! printf '%s' "$out" | grep -q -- "$pattern"; then
    echo "FAIL $name: exit $rc, output:"
    printf '%s\n' "$out"
    fails=$((fails + 1))
  else
    echo "ok   $name: $out"
  fi
}

expect "misspelt entry in file" "Centers" "$DENSIFY" misspelt.prm
expect "misspelt entry in --set" "Diametr" "$DENSIFY" good.prm --set "Particles/Diametr=2"
expect "misspelt subsection in --set" "Particle" "$DENSIFY" good.prm --set "Particle/Diameters=2"
expect "invalid value" "Polynomial degree" "$DENSIFY" good.prm --set "Mesh/Polynomial degree=3"
expect "negative diameter" "diameter -1" "$DENSIFY" good.prm --set "Particles/Diameters=-1"
expect "overlapping particles" "overlap" "$DENSIFY" good.prm \
  --set "Particles/Centres=0,0,1.25; 2,0,1.25"
expect "particle outside the die" "Die wall/Diameter" "$DENSIFY" good.prm \
  --set "Tools/Die wall/Enabled=true" --set "Tools/Die wall/Diameter=2"
expect "particle below the lower punch" "Lower punch" "$DENSIFY" good.prm \
  --set "Tools/Lower punch/Position=0.5"
expect "missing particle file" "missing.csv" "$DENSIFY" good.prm \
  --set "Particles/Particle file=missing.csv"
expect "missing parameter file" "nothing.prm" "$DENSIFY" nothing.prm
expect "unknown material" "unknown material 'Pb'" "$DENSIFY" good.prm --set "Particles/Materials=Pb"
expect "locking remedy on P2" "nodal averaging needs Mesh/Polynomial degree = 1" "$DENSIFY" good.prm \
  --set "Mesh/Polynomial degree=2" --set "Mesh/Volumetric locking remedy=nodal averaging"
expect "unknown option" "unknown option" "$DENSIFY" good.prm --frobnicate
expect "bad displacement table" "Displacement history" "$DENSIFY" good.prm \
  --set "Tools/Upper punch/Displacement history=0:0, 0:1"
expect "pole springs on the axis in a layer" "use 'vertical'" "$DENSIFY" good.prm \
  --set "Particles/Centres=0,0,1.25; 3,0,1.25" --set "Particles/Diameters=2.5" \
  --set "Contact/Friction coefficient=0" --set "Contact/Hold poles on axis=true"
expect "pole springs with friction" "frictionless" "$DENSIFY" good.prm \
  --set "Contact/Hold poles on axis=vertical"
expect "geometric tangent with CG" "Geometric tangent = auto" "$DENSIFY" good.prm \
  --set "Contact/Geometric tangent=true" --set "Solver/Linear solver=cg-amg"
expect "bad --set syntax" "Subsection/Name=value" "$DENSIFY" good.prm --set "Particles/Diameters"
# a stroke through the lower punch (the sphere of good.prm stands 2.5 mm
# high), or one that presses the spheres past the die's volume, before any
# mesh is built
expect "stroke beyond the lower punch" "reaches the lower punch" "$DENSIFY" good.prm \
  --set "Tools/Upper punch/Displacement history=0:0, 1:100"
expect "stroke past full density" "relative density" "$DENSIFY" good.prm \
  --set "Tools/Die wall/Enabled=true" --set "Tools/Die wall/Diameter=2.6" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:1.5"
# gmsh cannot mesh a sphere with elements larger than it
expect "element size above the particle" "Mesh/Element size = 100" "$DENSIFY" good.prm \
  --set "Mesh/Element size=100"
# a file that opens but cannot be read
expect "unreadable parameter file" "cannot read parameter file" "$DENSIFY" /proc/self/mem
# under MPI: every rank stops, one message, no hang
expect "overlap under mpirun -np 2" "overlap" "$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" good.prm \
  --set "Particles/Centres=0,0,1.25; 2,0,1.25"

echo "$fails failure(s)"
[ $fails -eq 0 ]
