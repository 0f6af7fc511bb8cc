# Explicit dynamics (Solver/Method = explicit) of a single tin sphere under a
# body force, on a coarse mesh with physical densities:
# 1. free flight: no tools; a body force b (along x) acts for the first
#    quarter of the load history and is then switched off. Afterwards the
#    sphere keeps its momentum: its mean velocity stays constant (to 1e-9)
#    and equals the impulse over the mass, b t / rho (to 1e-3), as
#    central differences conserve momentum exactly without external force.
# 2. at rest on the lower punch: gravity-like body force, damping; at the end
#    the punch carries the weight b V (to 1 %) and the kinetic energy is
#    small.
set -eu
cd "$WORK_DIR"
common=(--set "Output/Interval=0" --set "Mesh/Polynomial degree=1"
  --set "Mesh/Element size=0.6" --set "Mesh/Refinement directions="
  --set "Material/Finite strain=true" --set "Solver/Method=explicit"
  --set "Explicit/Mass scaling=none" --set "Explicit/Ramp fraction=0")

"$DENSIFY" "$SOURCE_DIR/prm/hertz.prm" "${common[@]}" \
  --set "Output/Directory=free" \
  --set "Tools/Lower punch/Enabled=false" --set "Tools/Upper punch/Enabled=false" \
  --set "Particles/Body force=0.01,0,0" \
  --set "Particles/Body force history=0:1, 0.25:1, 0.26:0, 1:0" \
  --set "Time stepping/Number of steps=4" \
  --set "Explicit/Loading time=4e-5" > free.log
/usr/bin/python3 - free/particles.csv <<'PY'
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1]))]
x = [float(r["mean_displacement_x"]) for r in rows]
y = [float(r["mean_displacement_y"]) for r in rows]
T, rho, b = 4e-5, 7.29e-9, 0.01
dt = T / 4
# impulse per volume: b over the first 0.25 T plus half of the 0.01 T ramp
v_expected = b * (0.25 + 0.005) * T / rho
v = [(x[i + 1] - x[i]) / dt for i in range(1, 3)]
print("velocity after the pulse: %.9g, %.9g mm/s (impulse / mass: %.9g)"
      % (v[0], v[1], v_expected))
assert abs(v[1] - v[0]) <= 1e-9 * abs(v[0]), "momentum not kept"
assert abs(v[0] / v_expected - 1) < 1e-3, "velocity is not impulse / mass"
assert max(abs(t) for t in y) < 1e-12 * abs(x[-1]), "sideways drift"
print("free particle keeps its momentum: yes")
PY

"$DENSIFY" "$SOURCE_DIR/prm/hertz.prm" "${common[@]}" \
  --set "Output/Directory=drop" \
  --set "Particles/Centres=0,0,1.26" \
  --set "Tools/Upper punch/Enabled=false" \
  --set "Particles/Body force=0,0,-50" \
  --set "Time stepping/Number of steps=4" \
  --set "Explicit/Damping ratio=0.3" \
  --set "Explicit/Loading time=2e-4" > drop.log
/usr/bin/python3 - drop/statistics.csv <<'PY'
import csv, sys
last = list(csv.DictReader(open(sys.argv[1])))[-1]
weight = 50 * float(last["particle_volume"])
force = float(last["lower_punch_force"])
ke, work = float(last["kinetic_energy"]), float(last["external_work"])
print("lower punch force %.6g N, weight b V %.6g N (ratio %.5f); "
      "kinetic energy %.3g of the work %.3g mJ"
      % (force, weight, force / weight, ke, work))
assert abs(force / weight - 1) < 0.01, "not at rest on the punch"
assert ke < 1e-3 * work
print("comes to rest at the static contact force: yes")
PY
