# Explicit dynamics (Solver/Method = explicit) against the implicit method on
# the light paper layer shrunk to 0.24 mm of stroke (seven J2 tin spheres,
# friction 0.2, tests/cli/lib/shrunk_light_scene.bash):
# - the punch force within 2 % of the implicit one and the relative density
#   within 0.1 points, at the end;
# - rate independence: twice the explicit steps (half the loading rate)
#   changes the punch force by less than 1 %;
# - the energy balance closes within 1 % of the external work;
# - 2 MPI ranks give the same statistics as 1 (to 1e-6) on the first steps.
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/shrunk_light_scene.bash"
"$DENSIFY" "$scene" "${common[@]}" --set "Output/Directory=implicit" > implicit.log
for n in 4000 8000; do
  "$DENSIFY" "$scene" "${common[@]}" --set "Output/Directory=explicit_$n" \
    --set "Solver/Method=explicit" --set "Explicit/Number of steps=$n" \
    > "explicit_$n.log" 2>&1
done
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
PY
# 1 and 2 ranks on the first two steps
for np in 1 2; do
  "$MPIEXEC" --oversubscribe -np $np "$DENSIFY" "$scene" "${common[@]}" \
    --set "Output/Directory=ranks_$np" --set "Solver/Method=explicit" \
    --set "Explicit/Number of steps=4000" --stop-after 2 > "ranks_$np.log" 2>&1 || [ $? -eq 3 ]
done
cut -d, -f1-7,15,25-40 ranks_1/statistics.csv > a.csv
cut -d, -f1-7,15,25-40 ranks_2/statistics.csv > b.csv
"$NUMDIFF" -q -r 1e-6 -a 1e-10 -s ', \n' a.csv b.csv
echo "1 and 2 ranks agree to 1e-6: yes"
