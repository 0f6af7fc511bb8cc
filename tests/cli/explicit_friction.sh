# Coulomb friction in explicit dynamics (Solver/Method = explicit): an elastic
# tin sphere pressed between two punches (friction 0.2 on both), then pulled
# sideways through its centre by a body force twice the friction limit, so
# that it slides on both punches. While it slides, every contact point is on
# the friction cone: the friction force of each punch over mu times its
# normal force is 1 (to 1e-3), and the friction work is positive. The
# sliding sphere accelerates (its kinetic energy reaches a quarter of the
# internal work): not quasi-static by design, so the quasi-static guard
# (Explicit/Maximum kinetic energy ratio) is off.
set -eu
cd "$WORK_DIR"
"$DENSIFY" "$SOURCE_DIR/prm/hertz.prm" --set "Output/Directory=slide" \
  --set "Output/Interval=0" --set "Mesh/Polynomial degree=1" \
  --set "Mesh/Element size=0.5" --set "Mesh/Refinement directions=" \
  --set "Material/Finite strain=true" \
  --set "Contact/Friction coefficient=0.2" \
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.03" \
  --set "Particles/Body force=12,0,0" \
  --set "Particles/Body force history=0:0, 1:0, 1.2:1, 2:1" \
  --set "Time stepping/End time=2" --set "Time stepping/Number of steps=10" \
  --set "Solver/Method=explicit" --set "Explicit/Number of steps=6000" \
  --set "Explicit/Damping ratio=0.05" \
  --set "Explicit/Maximum kinetic energy ratio=0" > slide.log
/usr/bin/python3 - slide/statistics.csv <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
pressed, last = rows[4], rows[-1]
N_up, N_low = float(last["upper_punch_force"]), float(last["lower_punch_force"])
f_up, f_low = float(last["upper_punch_friction"]), float(last["lower_punch_friction"])
pull = 12 * float(last["particle_volume"])
print("pressed: N = %.2f N; pulled by b V = %.2f N (limit 2 mu N = %.2f N)"
      % (float(pressed["upper_punch_force"]), pull, 0.4 * N_up))
r_up, r_low = f_up / (0.2 * N_up), f_low / (0.2 * N_low)
print("sliding: friction / (mu N) upper %.5f, lower %.5f; friction work %.4g mJ"
      % (r_up, r_low, float(last["friction_work"])))
assert pull > 1.5 * 0.4 * N_up, "not pulled beyond the limit"
assert abs(r_up - 1) < 1e-3 and abs(r_low - 1) < 1e-3
assert float(last["friction_work"]) > 0
print("friction / (mu N) = 1 within 1e-3 while sliding: yes")
PY
