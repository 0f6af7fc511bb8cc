# Explicit dynamics (Solver/Method = explicit) against the implicit method on
# the light paper layer shrunk to 0.24 mm of stroke (seven J2 tin spheres,
# friction 0.2, tests/cli/lib/shrunk_light_scene.bash):
# - the punch force within 2 % of the implicit one and the relative density
#   within 0.1 points, at the end;
# - rate independence: twice the explicit steps (half the loading rate)
#   changes the punch force by less than 1 %;
# - the energy balance closes within 1 % of the external work;
# - Explicit/End speed fraction = 0.5: the stations take the explicit steps
#   the slowing-down map gives them (the last station about 1.7 times the
#   second) and the punch force stays within 2 % of the implicit one;
# - Explicit/Step profile = 0:1, 0.6:1, 0.7:0.5: the stations ending at
#   0.7 and 0.8 s take twice the explicit steps of the one before, at half
#   its step and with a quarter of its scaled mass, and the punch force
#   stays within 2 % of the implicit one;
# - 2 MPI ranks give the same statistics as 1 (to 1e-6) on the first steps.
# Each run is a part of its own (tests/cli/lib/parts.bash).
# ctest parts: explicit_8000 implicit explicit_4000 slowing profile ranks_1 ranks_2:2
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/parts.bash"
source "$SOURCE_DIR/tests/cli/lib/shrunk_light_scene.bash"
explicit_run() {
  "$DENSIFY" "$scene" "${common[@]}" --set "Output/Directory=$1" \
    --set "Solver/Method=explicit" --set "Explicit/Number of steps=$2" \
    "${@:3}" > "$1.log" 2>&1 || { tail -n 3 "$1.log"; exit 1; }
}
part explicit_8000 && explicit_run explicit_8000 8000
part implicit &&
  { "$DENSIFY" "$scene" "${common[@]}" --set "Output/Directory=implicit" > implicit.log ||
    { tail -n 3 implicit.log; exit 1; }; }
part explicit_4000 && explicit_run explicit_4000 4000
part slowing && explicit_run slowing 2000 --set "Explicit/End speed fraction=0.5"
part profile && explicit_run profile 2000 --set "Explicit/Step profile=0:1, 0.6:1, 0.7:0.5"
# 1 and 2 ranks on the first two steps
for np in 1 2; do
  part ranks_$np || continue
  "$MPIEXEC" --oversubscribe -np $np "$DENSIFY" "$scene" "${common[@]}" \
    --set "Output/Directory=ranks_$np" --set "Solver/Method=explicit" \
    --set "Explicit/Number of steps=4000" --stop-after 2 > "ranks_$np.log" 2>&1 || [ $? -eq 3 ]
done
part check || exit 0
/usr/bin/python3 - <<'PY'
import csv
def last(d):
    return list(csv.DictReader(open(d + "/statistics.csv")))[-1]
im, ex, slow = last("implicit"), last("explicit_4000"), last("explicit_8000")
F = lambda r: float(r["upper_punch_force"])
rho = lambda r: 100 * float(r["relative_density"])
print("implicit: F_upper %.2f N, density %.3f %%" % (F(im), rho(im)))
for name, r in (("explicit 4000 steps", ex), ("explicit 8000 steps", slow)):
    print("%s: F_upper %.2f N (%+.2f %%), density %.3f %% (%+.3f points), "
          "KE/IE %.2g %%, energy balance %.2g %% of the external work"
          % (name, F(r), 100 * (F(r) / F(im) - 1), rho(r), rho(r) - rho(im),
             100 * float(r["kinetic_energy"]) / float(r["internal_work"]),
             100 * float(r["energy_balance"]) / float(r["external_work"])))
    assert abs(F(r) / F(im) - 1) < 0.02, "punch force"
    assert abs(rho(r) - rho(im)) < 0.1, "density"
    assert abs(float(r["energy_balance"])) < 0.01 * float(r["external_work"])
print("half the loading rate changes the punch force by %.2f %%"
      % (100 * abs(F(slow) / F(ex) - 1)))
assert abs(F(slow) / F(ex) - 1) < 0.01, "rate dependence"

# the slowing-down map: uniform time G(tau) = -ln(1 - a tau) / a (scene
# time in units of its end, a = 1 - End speed fraction); the steps of a
# station after the ramp are proportional to G's increase over it
import math, re
steps = [int(m) for m in re.findall(r"explicit (\d+) steps", open("slowing.log").read())]
assert len(steps) == 8, steps
G = lambda t: -math.log(1 - 0.5 * t) / 0.5
expected = (G(1) - G(7 / 8)) / (G(2 / 8) - G(1 / 8))
print("End speed fraction 0.5: explicit steps per station %s; last / second "
      "%.3f (map: %.3f)" % (steps, steps[-1] / steps[1], expected))
assert abs(steps[-1] / steps[1] / expected - 1) < 0.02, "time map"
r = last("slowing")
print("End speed fraction 0.5: F_upper %.2f N (%+.2f %%), KE/IE %.2g %%"
      % (F(r), 100 * (F(r) / F(im) - 1),
         100 * float(r["kinetic_energy"]) / float(r["internal_work"])))
assert abs(F(r) / F(im) - 1) < 0.02, "punch force, slowing down"

# the step profile: the stations ending at 0.7 and 0.8 s at half the step
text = open("profile.log").read()
steps = [int(m) for m in re.findall(r"explicit (\d+) steps", text)]
dts = [float(m) for m in re.findall(r"\(dt ([0-9.e+-]+) s\)", text)]
assert len(steps) == 8 and len(dts) == 8, (steps, dts)
print("Step profile 0:1, 0.6:1, 0.7:0.5: explicit steps per station %s, "
      "steps %s" % (steps, dts))
for k in (6, 7):
    assert abs(steps[k] / steps[5] / 2 - 1) < 0.02, "steps at half the step"
    assert dts[k] / dts[5] < 0.51, "half the step"
# and a quarter of the scaled mass (the cells flatten a little meanwhile)
rows = list(csv.DictReader(open("profile/statistics.csv")))
added = [float(r["added_mass"]) for r in rows]
print("Step profile: added mass at the last three stations %s"
      % ["%.4g" % a for a in added[5:]])
assert added[6] / added[5] < 0.26, "a quarter of the mass at half the step"
r = last("profile")
print("Step profile: F_upper %.2f N (%+.2f %%)"
      % (F(r), 100 * (F(r) / F(im) - 1)))
assert abs(F(r) / F(im) - 1) < 0.02, "punch force, step profile"
PY
cut -d, -f1-7,15,25-40 ranks_1/statistics.csv > a.csv
cut -d, -f1-7,15,25-40 ranks_2/statistics.csv > b.csv
"$NUMDIFF" -q -r 1e-6 -a 1e-10 -s ', \n' a.csv b.csv
echo "1 and 2 ranks agree to 1e-6: yes"
