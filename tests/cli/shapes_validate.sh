# Ellipsoids and STL particles in a particle file: --validate accepts a valid
# file (relative density from the exact shapes' volumes) and refuses
# overlapping non-spheres with one line naming both particles, exit 2.
# ctest processors: 1
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
cp "$SOURCE_DIR/tests/data/cube.stl" cube.stl
cat > base.prm <<'PRM'
subsection Particles
  set Particle file = shapes.csv
end
subsection Tools
  subsection Die wall
    set Enabled  = true
    set Diameter = 12
  end
end
subsection Output
  set Directory = out
end
PRM
# an ellipsoid lying on the lower punch (long axis along y), a sphere and
# the 2 mm cube beside it; the upper punch starts on the highest (the
# sphere's top at 3 mm)
cat > shapes.csv <<'CSV'
x,y,z,diameter,material,shape,diameter_y,diameter_z,angle_x,angle_y,angle_z
0,0,0.75,3,Sn,ellipsoid,2,1.5,0,0,90
2.5,0,1.5,3,Cu
-2.5,0,1,,Fe,cube.stl,0,0,0
CSV
out=$("$DENSIFY" --validate base.prm) || { echo "FAIL valid file: $out"; fails=$((fails + 1)); }
echo "$out"
# (pi/6 3^3 + 4/3 pi 1.5 1 0.75 + 8) / (pi 6^2 3) = 0.0791
if ! echo "$out" | grep -q "3 particle(s), relative density 7.91 % .* at 3.000 mm (the exact shapes' volumes); about"; then
  echo "FAIL relative density of the exact shapes"
  fails=$((fails + 1))
fi
# the ellipsoid turned so that its long axis reaches the sphere: its end
# 0.2 mm into it
sed 's/0,0,90$/0,0,0/; s/^2.5,0,1.5,3,Cu$/2.05,0,0.75,1.5,Cu/' shapes.csv > overlap.csv
expect_error "overlapping ellipsoid and sphere" 2 \
  "particles 0 and 1 overlap by at least 0.2" \
  "$DENSIFY" --validate base.prm --set "Particles/Particle file=overlap.csv"
# two ellipsoids crossed, one 0.18 mm into the other (the first's top at
# x = 1 is at z = 0.933, the second's bottom at 0.75)
cat > crossed.csv <<'CSV'
0,0,0.5,4,Sn,ellipsoid,1,1,0,0,0
1,0,1.25,4,Sn,ellipsoid,1,1,0,0,90
CSV
expect_error "crossed ellipsoids" 2 \
  "particles 0 and 1 overlap by at least 0.1" \
  "$DENSIFY" --validate base.prm --set "Particles/Particle file=crossed.csv"
# the ellipsoid's end 0.1 mm into the cube
sed 's/^-2.5,0,1,,Fe/-1.9,0,1,,Fe/' shapes.csv > cube_in.csv
expect_error "cube and ellipsoid" 2 "particles 0 and 2 overlap by at least 0.1 mm" \
  "$DENSIFY" --validate base.prm --set "Particles/Particle file=cube_in.csv"
# pole springs hold spheres only
expect_error "pole springs" 2 "Contact/Hold poles on axis is for spheres (particle 0" \
  "$DENSIFY" --validate base.prm --set "Contact/Hold poles on axis=vertical" \
  --set "Contact/Friction coefficient=0"
[ "$fails" -eq 0 ] || exit 1
echo ok
