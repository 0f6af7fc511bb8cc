#!/usr/bin/env python3
"""A die fill by discrete element dynamics (LIGGGHTS) for Densify.

Writes a LIGGGHTS input for a gravity fill of a cylindrical die, runs
`liggghts` until the bed settles and writes the particle file Densify reads:

  DIR/particles.csv   x,y,z,diameter,material in mm, the die axis on x = y = 0,
                      the bed standing on the lower punch at z = 0
                      (Particles/Particle file)
  DIR/bed.liggghts    the LIGGGHTS dump of the fill (id type x y z radius in
                      metres every --dump-every seconds, the last snapshot the
                      settled bed; Densify reads it directly too)
  DIR/in.fill, DIR/particles.data, DIR/liggghts.log   the input, the starting
                      cloud and LIGGGHTS' log

The particles start as a loose cloud over the die (a jittered lattice with
small random velocities; sizes and materials drawn with --seed), fall under
gravity onto the floor (z = 0) between the die wall (a cylinder about the z
axis) and come to rest (Hertz-Mindlin contacts with friction and damping,
reduced stiffness); the run stops when the kinetic energy per particle falls
below --settle times m g d. With --fill-height the particles whose top lies
above that height are struck off (as a feed shoe would) and the rest settles
again. DEM contacts overlap a little (0.06 to 0.9 % of d at the default
stiffness in the fills of doc/user_guide.md, "A die fill by LIGGGHTS");
before writing the CSV the particles are moved apart until none overlaps
another, the die wall or the floor (as Densify does when it reads the dump
directly).

Usage:
  bash scripts/packing/liggghts_fill.sh --die-diameter 20 --particles 200 \\
      --diameters 2,3 --materials Sn:0.7,Fe:0.3 --seed 1 --out output/fill
  bash scripts/packing/liggghts_fill.sh --convert DUMP --die-diameter 20 \\
      --materials Sn,Fe --out DIR  # only convert a dump's last snapshot
"""

import argparse
import math
import os
import random
import shutil
import subprocess
import sys
import time

import numpy as np

# mass densities (kg/m^3) of Densify's material presets (doc/materials.md)
DENSITY = {"Sn": 7290.0, "Fe": 7874.0, "Cu": 8960.0}
DEFAULT_DENSITY = 7500.0
GRAVITY = 9.81
# most Jacobi sweeps that move the DEM overlaps apart
SWEEPS = 100000


def fail(message):
    """One line on stderr, exit code 2."""
    print("liggghts_fill: " + message, file=sys.stderr)
    sys.exit(2)


def parse_materials(text):
    """'Sn' or 'Sn,Fe' (names) or 'Sn:0.7,Fe:0.3' (fractions): [(name, fraction)]."""
    items = [item.strip() for item in text.split(",") if item.strip()]
    if not items:
        fail("--materials: give a name (Sn) or fractions (Sn:0.7,Fe:0.3)")
    result = []
    for item in items:
        if ":" in item:
            name, value = item.split(":", 1)
            try:
                fraction = float(value)
            except ValueError:
                fraction = -1
            if not fraction >= 0:
                fail("--materials: '%s' is not name:fraction with a fraction >= 0"
                     % item)
            result.append((name.strip(), fraction))
        else:
            result.append((item, None))
    if all(f is None for _, f in result):
        if len(result) > 1:
            # names only: the atom types of a dump to convert
            return [(name, None) for name, _ in result]
        return [(result[0][0], 1.0)]
    if any(f is None for _, f in result):
        fail("--materials: give every name a fraction (Sn:0.7,Fe:0.3) or none")
    total = sum(f for _, f in result)
    if abs(total - 1) > 1e-6:
        fail("--materials: the fractions add up to %g, not 1" % total)
    return result


def parse_diameters(text):
    """'2.5' (equal) or '2,3' (uniform between): (dmin, dmax) in mm."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) == 1 and values[0] > 0:
        return values[0], values[0]
    if len(values) == 2 and 0 < values[0] < values[1]:
        return values[0], values[1]
    fail("--diameters: give one diameter (2.5, equal spheres) or 'dmin,dmax' "
         "with 0 < dmin < dmax (uniform), in mm, not '%s'" % text)


def material_counts(mixture, n):
    """Whole particles per material: floor, then the largest remainders."""
    counts = [int(math.floor(f * n)) for _, f in mixture]
    order = sorted(range(len(mixture)),
                   key=lambda k: -(mixture[k][1] * n - counts[k]))
    k = 0
    while sum(counts) < n:
        counts[order[k % len(order)]] += 1
        k += 1
    return counts


def rayleigh_time(radius, density, youngs, poisson):
    """Rayleigh wave time of a sphere (s), the usual DEM time step scale."""
    shear = youngs / (2 * (1 + poisson))
    return math.pi * radius * math.sqrt(density / shear) / (
        0.1631 * poisson + 0.8766)


# ---------------------------------------------------------------------------
# the dump and the overlaps


def read_dump(path):
    """The last snapshot of a LIGGGHTS/LAMMPS text dump: ids, types, centres
    (m) and radii (m), sorted by id."""
    with open(path) as f:
        lines = f.read().splitlines()
    starts = [i for i, line in enumerate(lines)
              if line.strip() == "ITEM: TIMESTEP"]
    if not starts:
        fail("%s: no 'ITEM: TIMESTEP' (not a LIGGGHTS dump)" % path)
    i = starts[-1]
    n = None
    while i < len(lines):
        line = lines[i].strip()
        if line.startswith("ITEM: NUMBER OF ATOMS"):
            n = int(lines[i + 1])
            i += 2
        elif line.startswith("ITEM: ATOMS"):
            columns = line.split()[2:]
            break
        else:
            i += 1
    else:
        fail("%s: the last snapshot has no 'ITEM: ATOMS'" % path)
    if not n:
        fail("%s: the last snapshot has no atoms" % path)

    def column(*names):
        for name in names:
            if name in columns:
                return columns.index(name)
        fail("%s:%d: the ATOMS line has no column %s" % (path, i + 1,
                                                          " or ".join(names)))

    k_x, k_y, k_z = column("x", "xu"), column("y", "yu"), column("z", "zu")
    k_r = column("radius", "diameter")
    scale = 0.5 if columns[k_r] == "diameter" else 1.0
    if i + n >= len(lines):
        fail("%s: the last snapshot is cut short" % path)
    rows = [lines[i + 1 + a].split() for a in range(n)]
    if any(len(row) < len(columns) for row in rows):
        fail("%s: a row of the last snapshot has too few fields" % path)
    data = np.array([[float(row[columns.index(name)]) if name in columns
                      else default for name, default in
                      (("id", a + 1), ("type", 1))] +
                     [float(row[k]) for k in (k_x, k_y, k_z)] +
                     [scale * float(row[k_r])]
                     for a, row in enumerate(rows)])
    data = data[np.argsort(data[:, 0], kind="stable")]
    return (data[:, 0].astype(int), data[:, 1].astype(int), data[:, 2:5],
            data[:, 5])


def close_pairs(c, r, margin):
    """Index pairs (i < j) whose gap is below margin (all pairs checked)."""
    first, second = [], []
    for i in range(len(r) - 1):
        d = np.linalg.norm(c[i + 1:] - c[i], axis=1)
        j = np.nonzero(d < r[i] + r[i + 1:] + margin)[0] + i + 1
        first.extend([i] * len(j))
        second.extend(j.tolist())
    return np.array(first, dtype=int), np.array(second, dtype=int)


def clamp(c, r, die_radius, floor):
    """Put every particle inside the die and on or above the floor."""
    below = c[:, 2] - r < floor
    c[below, 2] = floor + r[below]
    rho = np.sqrt(c[:, 0] * c[:, 0] + c[:, 1] * c[:, 1])
    out = rho + r > die_radius
    c[out, 0:2] *= ((die_radius - r[out]) / rho[out])[:, None]


def separate(c, r, die_radius, floor, limit=0.05):
    """Move DEM contact overlaps apart (the method of Densify's
    separate_overlaps()): Jacobi sweeps, each pair closer than 1e-6 of the
    smallest diameter pushed apart along its centre line to that gap, half
    each, a particle moved by the sum of its pushes, then put back inside the
    die and onto or above the floor; until no pair overlaps. Returns
    (largest overlap, largest shift, sweeps)."""
    n = len(r)
    d_min = 2 * r.min()
    gap = 1e-6 * d_min
    rho = np.sqrt(c[:, 0] * c[:, 0] + c[:, 1] * c[:, 1])
    worst = max(0.0, ((rho + r - die_radius) / (2 * r)).max(),
                ((floor - (c[:, 2] - r)) / (2 * r)).max())
    margin = 0.1 * d_min
    i, j = close_pairs(c, r, margin)
    if len(i):
        overlap = r[i] + r[j] - np.sqrt(((c[j] - c[i]) ** 2).sum(axis=1))
        worst = max(worst, (overlap / (2 * np.minimum(r[i], r[j]))).max())
    largest = worst
    if worst > limit:
        fail("overlaps of %.3g %% of a diameter: more than DEM contacts "
             "(at most %g %%); is the dump in metres, with the die axis on "
             "x = y = 0 and the floor at z = 0, and the die diameter right?"
             % (100 * worst, 100 * limit))
    start = c.copy()
    built = c.copy()
    clamp(c, r, die_radius, floor)
    for sweep in range(SWEEPS):
        if np.abs(c - built).max() > margin / 2:
            i, j = close_pairs(c, r, margin)
            built = c.copy()
        if len(i) == 0:
            break
        v = c[j] - c[i]
        dist = np.sqrt((v * v).sum(axis=1))
        if (r[i] + r[j] - dist).max() <= 0:
            break
        push = r[i] + r[j] + gap - dist
        active = push > 0
        half = (0.5 * push[active] / dist[active])[:, None] * v[active]
        shift = np.zeros_like(c)
        np.add.at(shift, i[active], -half)
        np.add.at(shift, j[active], half)
        c += shift
        clamp(c, r, die_radius, floor)
    else:
        fail("the overlapping particles could not be moved apart in %d "
             "sweeps" % SWEEPS)
    return largest, np.sqrt(((c - start) ** 2).sum(axis=1)).max(), sweep


def convert(dump, die_diameter, names, out_csv, header):
    """Read the dump's last snapshot, move its overlaps apart, write the CSV;
    returns (number of particles, top (mm), largest overlap, largest shift,
    centres, radii)."""
    _, types, centres, radii = read_dump(dump)
    c = 1000 * centres
    r = 1000 * radii
    if not (r > 0).all():
        fail("%s: a radius is not > 0" % dump)
    if types.max() > len(names) and len(names) > 1:
        fail("%s: atom type %d, but only %d material names"
             % (dump, types.max(), len(names)))
    largest, shift, _ = separate(c, r, die_diameter / 2, 0.0)
    with open(out_csv, "w") as f:
        for line in header:
            f.write("# " + line + "\n")
        f.write("x,y,z,diameter,material\n")
        for k in range(len(r)):
            name = names[types[k] - 1] if len(names) > 1 else names[0]
            f.write("%.9f,%.9f,%.9f,%.9f,%s\n"
                    % (c[k, 0], c[k, 1], c[k, 2], 2 * r[k], name))
    return len(r), (c[:, 2] + r).max(), largest, shift, c, r


# ---------------------------------------------------------------------------
# the fill


def starting_cloud(args, dmin, dmax, mixture, rng):
    """Diameters (mm), atom types and the positions (mm) of the cloud."""
    R = args.die_diameter / 2
    if args.particles:
        n = args.particles
    else:
        # enough for the fill height at a dense random packing (0.64)
        mean_volume = math.pi / 6 * (dmin + dmax) * (dmin ** 2 + dmax ** 2) / 4
        n = int(math.ceil(0.64 * math.pi * R * R * args.fill_height
                          / mean_volume)) + 1
    if dmin == dmax:
        diameters = [dmin] * n
    else:
        diameters = [rng.uniform(dmin, dmax) for _ in range(n)]
    types = []
    for k, count in enumerate(material_counts(mixture, n)):
        types += [k + 1] * count
    rng.shuffle(types)
    # a lattice of spacing 1.2 dmax inside the die, layer by layer upwards
    s = 1.2 * dmax
    reach = R - 0.6 * dmax
    if reach < 0:
        fail("--die-diameter %g mm is below 1.2 times the largest diameter"
             % args.die_diameter)
    k = int(reach / s)
    sites = [(a * s, b * s) for a in range(-k, k + 1) for b in range(-k, k + 1)
             if math.hypot(a * s, b * s) <= reach]
    positions = []
    z = 0.6 * dmax
    while len(positions) < n:
        for x, y in sites:
            if len(positions) == n:
                break
            jitter = 0.1 * dmax
            px = x + rng.uniform(-jitter, jitter)
            py = y + rng.uniform(-jitter, jitter)
            rho = math.hypot(px, py)
            if rho > reach:
                px, py = px * reach / rho, py * reach / rho
            positions.append((px, py, z + rng.uniform(-jitter, jitter)))
        z += s
    return diameters, types, positions


def write_data(path, args, diameters, types, positions, names, rng):
    """The starting cloud as a LAMMPS data file (SI units)."""
    R = args.die_diameter / 2
    dmax = max(diameters)
    top = max(p[2] for p in positions) + dmax
    with open(path, "w") as f:
        f.write("Densify die fill: %d particles\n\n" % len(diameters))
        f.write("%d atoms\n%d atom types\n\n" % (len(diameters), len(names)))
        lo, hi = -(R + dmax) / 1000, (R + dmax) / 1000
        f.write("%.9g %.9g xlo xhi\n%.9g %.9g ylo yhi\n" % (lo, hi, lo, hi))
        f.write("%.9g %.9g zlo zhi\n\n" % (-dmax / 1000, top / 1000))
        f.write("Atoms\n\n")
        for k, (d, t, p) in enumerate(zip(diameters, types, positions)):
            rho = DENSITY.get(names[t - 1], DEFAULT_DENSITY)
            f.write("%d %d %.12g %.9g %.12g %.12g %.12g\n"
                    % (k + 1, t, d / 1000, rho, p[0] / 1000, p[1] / 1000,
                       p[2] / 1000))
        # small random velocities (m/s) that break the lattice's symmetry
        f.write("\nVelocities\n\n")
        for k in range(len(diameters)):
            v = [rng.uniform(-0.05, 0.05) for _ in range(3)]
            f.write("%d %.6g %.6g %.6g 0 0 0\n" % (k + 1, v[0], v[1], v[2]))
    return top


def write_input(path, args, n_types, dt, chunk, settle_energy, dmin, dmax):
    """The LIGGGHTS input: contacts, walls, gravity, the settling loop."""
    R = args.die_diameter / 2000
    per_type = " ".join(["%g"] * n_types)
    pairs = n_types * n_types
    e, mu, nu, E = args.restitution, args.friction, 0.3, args.youngs_modulus
    chunks = int(math.ceil(args.max_time / (chunk * dt)))
    strike = ""
    if args.fill_height:
        strike = """
# strike off what stands above the fill height, then settle again
variable above atom "z+c_rad > {h:.9g}"
group strike variable above
delete_atoms group strike
variable m loop {chunks}
label settle_again
run {chunk}
if "${{ke}} < {energy:.6g}" then "jump SELF struck"
next m
jump SELF settle_again
label struck
""".format(h=args.fill_height / 1000, chunks=chunks, chunk=chunk,
           energy=settle_energy)
    text = """# Densify die fill (scripts/packing/liggghts_fill.py), SI units
atom_style granular
atom_modify map array
boundary m m m
newton off
communicate single vel yes
units si
read_data particles.data
neighbor {skin:.6g} bin
neigh_modify delay 0

fix m1 all property/global youngsModulus peratomtype {E}
fix m2 all property/global poissonsRatio peratomtype {nu}
fix m3 all property/global coefficientRestitution peratomtypepair {n} {e}
fix m4 all property/global coefficientFriction peratomtypepair {n} {mu}
pair_style gran model hertz tangential history
pair_coeff * *
timestep {dt:.6g}

fix gravity all gravity {g} vector 0.0 0.0 -1.0
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix die all wall/gran model hertz tangential history primitive type 1 zcylinder {R:.9g} 0.0 0.0
fix integrate all nve/sphere

compute rad all property/atom radius
variable top atom z+c_rad
compute top all reduce max v_top
thermo_style custom step atoms ke c_top
thermo {chunk}
thermo_modify lost error norm no
variable ke equal ke
dump bed all custom {chunk} bed.liggghts id type x y z radius
dump_modify bed format "%d %d %.10g %.10g %.10g %.10g"

# fall and settle: until the kinetic energy is below {energy:.6g} J
variable k loop {chunks}
label settle
run {chunk}
if "${{ke}} < {energy:.6g}" then "jump SELF settled"
next k
jump SELF settle
label settled
{strike}variable step equal step
variable atoms equal atoms
variable bedtop equal c_top
print "DENSIFY settled at step ${{step}} with ${{atoms}} particles, top ${{bedtop}} m, kinetic energy ${{ke}} J"
""".format(skin=0.25 * dmax / 1000,
           E=per_type % ((E,) * n_types), nu=per_type % ((nu,) * n_types),
           n=n_types, e=" ".join(["%g" % e] * pairs),
           mu=" ".join(["%g" % mu] * pairs), dt=dt, g=GRAVITY, R=R,
           chunk=chunk, chunks=chunks, energy=settle_energy, strike=strike)
    with open(path, "w") as f:
        f.write(text)


def main():
    parser = argparse.ArgumentParser(
        prog="liggghts_fill.sh",
        description="A gravity fill of a cylindrical die by LIGGGHTS, "
        "written as Densify's particle file (mm).")
    parser.add_argument("--die-diameter", type=float, required=True,
                        help="inner die diameter (mm)")
    parser.add_argument("--particles", type=int, default=0,
                        help="number of particles to pour")
    parser.add_argument("--fill-height", type=float, default=0,
                        help="strike off the particles whose top is above "
                        "this height (mm); without --particles, enough are "
                        "poured to reach it")
    parser.add_argument("--diameters", default="2.5",
                        help="'d' (equal spheres) or 'dmin,dmax' (uniform "
                        "between), mm; default 2.5")
    parser.add_argument("--materials", default="Sn",
                        help="'Sn' or a mixture by number 'Sn:0.7,Fe:0.3' "
                        "(atom types 1, 2, ... in this order); with --convert "
                        "the name of each atom type, 'Sn,Fe'")
    parser.add_argument("--seed", type=int, default=1,
                        help="seed of sizes, materials and the starting cloud")
    parser.add_argument("--out", default="output/liggghts_fill",
                        help="output directory")
    parser.add_argument("--friction", type=float, default=0.3,
                        help="Coulomb friction of particles and walls")
    parser.add_argument("--restitution", type=float, default=0.3,
                        help="coefficient of restitution")
    parser.add_argument("--youngs-modulus", type=float, default=5e7,
                        help="Young's modulus of the DEM contacts (Pa; "
                        "reduced, as usual in DEM: overlaps scale with "
                        "E^(-2/3), the time step with E^(-1/2))")
    parser.add_argument("--settle", type=float, default=1e-6,
                        help="settled when the kinetic energy per particle "
                        "is below this times m g d")
    parser.add_argument("--max-time", type=float, default=5,
                        help="most simulated time per settling (s)")
    parser.add_argument("--liggghts", default="liggghts",
                        help="the LIGGGHTS executable")
    parser.add_argument("--convert", metavar="DUMP",
                        help="only convert the last snapshot of DUMP to "
                        "OUT/particles.csv")
    args = parser.parse_args()
    if args.die_diameter <= 0:
        fail("--die-diameter must be > 0 mm")
    os.makedirs(args.out, exist_ok=True)
    csv = os.path.join(args.out, "particles.csv")
    mixture = parse_materials(args.materials)
    names = [name for name, _ in mixture]
    command = "bash scripts/packing/liggghts_fill.sh " + " ".join(
        a if " " not in a else "'%s'" % a for a in sys.argv[1:])

    if args.convert:
        n, top, largest, shift, _, _ = convert(
            args.convert, args.die_diameter, names, csv,
            ["from the last snapshot of " + args.convert, command])
        print("%s: %d particles, top %.4f mm; DEM overlaps up to %.3g %% of "
              "a diameter moved apart (shifts up to %.3g mm)"
              % (csv, n, top, 100 * largest, shift))
        return

    if args.particles <= 0 and args.fill_height <= 0:
        fail("give --particles N or --fill-height H (mm), or both")
    if any(f is None for _, f in mixture):
        fail("--materials: a fill takes one name or fractions "
             "(Sn:0.7,Fe:0.3)")
    if shutil.which(args.liggghts) is None:
        fail("no '%s': install LIGGGHTS (Debian: apt-get install liggghts)"
             % args.liggghts)
    dmin, dmax = parse_diameters(args.diameters)
    rng = random.Random(args.seed)
    diameters, types, positions = starting_cloud(args, dmin, dmax, mixture,
                                                 rng)
    write_data(os.path.join(args.out, "particles.data"), args, diameters,
               types, positions, names, rng)
    densest = max(DENSITY.get(name, DEFAULT_DENSITY) for name in names)
    dt = 0.1 * rayleigh_time(dmin / 2000, densest, args.youngs_modulus, 0.3)
    chunk = max(1, int(round(0.01 / dt)))  # a check every 0.01 s
    mean_d = sum(diameters) / len(diameters) / 1000
    mean_mass = sum(DENSITY.get(names[t - 1], DEFAULT_DENSITY) * math.pi / 6
                    * (d / 1000) ** 3 for d, t in zip(diameters, types)) / len(
                        diameters)
    settle_energy = args.settle * len(diameters) * mean_mass * GRAVITY * mean_d
    write_input(os.path.join(args.out, "in.fill"), args, len(names), dt, chunk,
                settle_energy, dmin, dmax)
    for old in ("bed.liggghts", "particles.csv"):
        if os.path.exists(os.path.join(args.out, old)):
            os.remove(os.path.join(args.out, old))

    start = time.time()
    with open(os.path.join(args.out, "liggghts.log"), "w") as log:
        rc = subprocess.call([args.liggghts, "-in", "in.fill", "-log", "none"],
                             cwd=args.out, stdout=log, stderr=subprocess.STDOUT)
    seconds = time.time() - start
    with open(os.path.join(args.out, "liggghts.log")) as log:
        text = log.read()
    summary = [line for line in text.splitlines()
               if line.startswith("DENSIFY settled")]
    if rc != 0 or not summary:
        errors = [line for line in text.splitlines() if "ERROR" in line]
        fail("LIGGGHTS failed (exit %d): %s (%s)" % (
            rc, errors[0] if errors else "see the log",
            os.path.join(args.out, "liggghts.log")))
    steps = int(summary[-1].split()[4])
    simulated = steps * dt
    if not float(summary[-1].split()[-2]) < settle_energy:
        fail("the bed did not settle in %g s of simulated time: raise "
             "--max-time or --settle" % args.max_time)

    n, top, largest, shift, c, r = convert(
        os.path.join(args.out, "bed.liggghts"), args.die_diameter, names, csv,
        ["LIGGGHTS die fill, %s" % command,
         "settled after %.3g s simulated (%d steps of %.3g s)"
         % (simulated, steps, dt)])
    R = args.die_diameter / 2
    fraction = (np.pi / 6 * (2 * r) ** 3).sum() / (np.pi * R * R * top)
    print("LIGGGHTS fill: %d particles settled after %.3g s simulated "
          "(%d steps) in %.1f s" % (n, simulated, steps, seconds))
    print("bed: top %.4f mm, %.2f %% of the die up to the top, DEM overlaps "
          "up to %.3g %% of a diameter moved apart (shifts up to %.3g mm)"
          % (top, 100 * fraction, 100 * largest, shift))
    if args.fill_height and top < args.fill_height - dmax:
        print("liggghts_fill: warning: the bed reaches %.3f mm, below the "
              "fill height: pour more particles" % top, file=sys.stderr)
    print("written: %s and %s (the dump's atom types: %s)"
          % (csv, os.path.join(args.out, "bed.liggghts"),
             ", ".join("%d = %s" % (k + 1, name)
                       for k, name in enumerate(names))))
    print("Densify: --set \"Particles/Particle file=%s\" --set \"Tools/Die "
          "wall/Diameter=%g\"" % (csv, args.die_diameter))


if __name__ == "__main__":
    main()
