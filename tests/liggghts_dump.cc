// A LIGGGHTS dump as the particle file (liggghts_dump.h):
// - tests/data/die_fill.liggghts, a die fill by LIGGGHTS written by
//     bash scripts/packing/liggghts_fill.sh --die-diameter 8
//       --particles 12 --diameters 2,3 --materials Sn:0.5,Cu:0.5 --seed 3
//       --out die_fill
//   (of its 72 snapshots the first, the middle and the last are kept): the
//   last snapshot's positions, diameters (metres to mm) and materials (atom
//   type 1 Sn, 2 Cu) are read, in the order of the atom ids, through
//   read_particle_csv() as Densify reads Particles/Particle file;
// - its DEM contact overlaps moved apart (separate_overlaps()) give the
//   particles of tests/data/die_fill.csv, which the script wrote from the
//   same dump by the same method, to 1e-6 mm, and pass check_particles();
// - the columns are found by name (xu yu zu, diameter, no id, no type);
// - each malformed dump gives one line naming the parameter, the file and
//   the line; overlaps beyond a DEM contact's name the parameter to check.
#include <densify/geometry/liggghts_dump.h>
#include <densify/geometry/particles.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

using namespace densify;

using densify::testing::write_file;
using densify::testing::yes;

namespace
{



  /// Print the particles.
  void
  print(const std::vector<Particle> &particles)
  {
    for (unsigned int i = 0; i < particles.size(); ++i)
      std::cout << "  particle " << i << ": centre (" << particles[i].centre[0]
                << ", " << particles[i].centre[1] << ", "
                << particles[i].centre[2] << ") diameter "
                << particles[i].diameter << " material "
                << particles[i].material << std::endl;
  }



  /// Read @p name as Densify reads the particle file, print the particles
  /// or the error message; an unexpected outcome is a failure.
  std::vector<Particle>
  read(const std::string &name,
       const std::string &materials,
       const bool         expect_error)
  {
    try
      {
        const std::vector<Particle> particles =
          read_particle_csv(name, materials);
        std::cout << name << ": " << particles.size() << " particles"
                  << std::endl;
        print(particles);
        if (expect_error)
          std::cout << "  expected an error: " << yes(false) << std::endl;
        return particles;
      }
    catch (const std::runtime_error &e)
      {
        std::cout << e.what() << std::endl;
        if (!expect_error)
          std::cout << "  unexpected error: " << yes(false) << std::endl;
        return {};
      }
  }



  /// A dump of one snapshot: the ATOMS line's columns and rows.
  std::string
  dump(const std::string &columns, const std::string &rows, int n = -1)
  {
    if (n < 0)
      n = std::count(rows.begin(), rows.end(), '\n');
    return "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n" + std::to_string(n) +
           "\nITEM: BOX BOUNDS ff ff ff\n-0.01 0.01\n-0.01 0.01\n0 0.02\n"
           "ITEM: ATOMS " +
           columns + "\n" + rows;
  }
} // namespace



int
main()
{
  const std::string data = testing::source_dir() + "/tests/data/";

  // the stored fill, read as the particle file
  std::cout << "is a dump: "
            << yes(is_liggghts_dump(data + "die_fill.liggghts"))
            << "; the CSV is not: "
            << yes(!is_liggghts_dump(data + "die_fill.csv")) << std::endl;
  std::vector<Particle> bed;
  try
    {
      bed = read_particle_csv(data + "die_fill.liggghts", "Sn, Cu");
    }
  catch (const std::runtime_error &e)
    {
      std::cout << e.what() << ": " << yes(false) << std::endl;
      return 1;
    }
  std::cout << "tests/data/die_fill.liggghts, last snapshot (timestep 96915): "
            << bed.size() << " particles (mm)" << std::endl;
  print(bed);
  unsigned int n_sn = 0;
  for (const Particle &p : bed)
    n_sn += p.material == "Sn" ? 1 : 0;
  std::cout << "types 1 and 2 as Sn and Cu, 6 each: " << yes(n_sn == 6)
            << std::endl;
  bool all_fe = true;
  for (const Particle &p : read_particle_csv(data + "die_fill.liggghts", "Fe"))
    all_fe = all_fe && p.material == "Fe";
  std::cout << "one name in Particles/Materials: every particle Fe: "
            << yes(all_fe) << std::endl;

  // its overlaps moved apart, as the script did for the CSV
  Container die;
  die.has_die                       = true;
  die.die_radius                    = 4;
  die.has_lower                     = true;
  die.lower_z                       = 0;
  std::vector<Particle>   separated = bed;
  const OverlapSeparation s =
    separate_overlaps(separated, die, "tests/data/die_fill.liggghts");
  std::cerr << "separate_overlaps: " << s.sweeps << " sweeps" << std::endl;
  std::cout << "largest DEM overlap " << 100 * s.largest_overlap
            << " % of a diameter, largest shift below 0.01 mm: "
            << yes(s.largest_shift < 0.01) << std::endl;
  const std::vector<Particle> csv =
    read_particle_csv(data + "die_fill.csv", "Sn");
  double largest = 0;
  bool   same    = csv.size() == separated.size();
  for (unsigned int i = 0; same && i < csv.size(); ++i)
    {
      largest = std::max(largest, csv[i].centre.distance(separated[i].centre));
      same = same && std::abs(csv[i].diameter - separated[i].diameter) < 1e-8 &&
             csv[i].material == separated[i].material;
    }
  std::cerr << "largest distance from the script's CSV: " << largest << " mm"
            << std::endl;
  std::cout << "the same particles as tests/data/die_fill.csv (to 1e-6 mm): "
            << yes(same && largest < 1e-6) << std::endl;
  double top = 0;
  for (const Particle &p : separated)
    top = std::max(top, p.centre[2] + p.diameter / 2);
  die.has_upper       = true;
  die.upper_z         = top;
  std::string checked = "ok";
  try
    {
      check_particles(separated, die, 1e-9 * top);
    }
  catch (const std::runtime_error &e)
    {
      checked = e.what();
    }
  std::cout << "no overlaps left, all in the die (check_particles): "
            << yes(checked == "ok") << std::endl;
  std::string before = "ok";
  try
    {
      check_particles(bed, die, 1e-9 * top);
    }
  catch (const std::runtime_error &e)
    {
      before = e.what();
    }
  std::cout << "the DEM bed itself overlaps: " << yes(before != "ok")
            << std::endl;

  // columns by name; the last snapshot
  const std::string rows = "1 1 0.001 0 0.00125 0.00125\n"
                           "2 2 -0.0015 0 0.001 0.001\n";
  write_file("two.liggghts",
             dump("id type x y z radius", "1 1 0.002 0 0.00125 0.00125\n") +
               dump("id type x y z radius", rows));
  read("two.liggghts", "Sn,Cu", false);
  write_file("columns.liggghts",
             dump("zu diameter yu xu vx",
                  "0.00125 0.0025 0 0.001 7\n0.001 0.002 0 -0.0015 8\n"));
  read("columns.liggghts", "Fe", false);
  write_file("ids.liggghts",
             dump("type x y z radius id",
                  "2 -0.0015 0 0.001 0.001 9\n1 0.001 0 0.00125 0.00125 4\n"));
  read("ids.liggghts", "Sn, Cu", false);

  // malformed dumps: one line each
  write_file("empty.liggghts", dump("id type x y z radius", "", 0));
  read("empty.liggghts", "Sn", true);
  write_file("no-atoms-item.liggghts",
             "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n2\n");
  read("no-atoms-item.liggghts", "Sn", true);
  write_file(
    "no-count.liggghts",
    "ITEM: TIMESTEP\n5\nITEM: ATOMS id type x y z radius\n1 1 0 0 1 1\n");
  read("no-count.liggghts", "Sn", true);
  write_file("no-radius.liggghts", dump("id type x y z", "1 1 0 0 0.001\n"));
  read("no-radius.liggghts", "Sn", true);
  write_file("no-z.liggghts", dump("id type x y radius", "1 1 0 0 0.001\n"));
  read("no-z.liggghts", "Sn", true);
  write_file("scaled.liggghts",
             dump("id type xs ys zs radius", "1 1 0.5 0.5 0.1 0.001\n"));
  read("scaled.liggghts", "Sn", true);
  write_file("zero-radius.liggghts",
             dump("id type x y z radius",
                  "1 1 0 0 0.001 0.001\n2 1 0 0 0.003 0\n"));
  read("zero-radius.liggghts", "Sn", true);
  write_file("negative-radius.liggghts",
             dump("id type x y z radius", "1 1 0 0 0.001 -1e-3\n"));
  read("negative-radius.liggghts", "Sn", true);
  write_file("cut-short.liggghts",
             dump("id type x y z radius", "1 1 0 0 0.001 0.001\n", 3));
  read("cut-short.liggghts", "Sn", true);
  write_file("short-row.liggghts",
             dump("id type x y z radius",
                  "1 1 0 0 0.001 0.001\n2 1 0 0.003\n"));
  read("short-row.liggghts", "Sn", true);
  write_file("not-a-number.liggghts",
             dump("id type x y z radius", "1 1 0 0 abc 0.001\n"));
  read("not-a-number.liggghts", "Sn", true);
  write_file("bad-type.liggghts",
             dump("id type x y z radius", "1 0 0 0 1 1\n"));
  read("bad-type.liggghts", "Sn", true);
  write_file("third-type.liggghts",
             dump("id type x y z radius",
                  "1 1 0 0 0.001 0.001\n2 3 0 0 3 1\n"));
  read("third-type.liggghts", "Sn, Cu", true);
  write_file("twice.liggghts",
             dump("id type x y z radius",
                  "1 1 0 0 0.001 0.001\n1 1 0.003 0 0.001 0.001\n"));
  read("twice.liggghts", "Sn", true);
  write_file("no-timestep.liggghts", "ITEM: UNITS\nsi\n");
  read("no-timestep.liggghts", "Sn", true);

  // overlaps beyond a DEM contact's: wrong units, origin or die
  const std::vector<std::pair<std::string, std::vector<Particle>>> wrong = {
    {"particles overlapping by 20 %",
     {{Point<3>(0, 0, 1), 2., "Sn"}, {Point<3>(0, 0, 2.6), 2., "Sn"}}},
    {"a particle crossing the die wall by 10 %",
     {{Point<3>(3.2, 0, 1), 2., "Sn"}}},
    {"a particle 10 % below the lower punch",
     {{Point<3>(0, 0, 0.8), 2., "Sn"}}}};
  for (const auto &[what, particles] : wrong)
    {
      std::vector<Particle> p = particles;
      try
        {
          separate_overlaps(p, die, "Particles/Particle file: 'x' (test)");
          std::cout << what << ": no error: " << yes(false) << std::endl;
        }
      catch (const std::runtime_error &e)
        {
          std::cout << what << ": " << e.what() << std::endl;
          std::cout << "  nothing moved: "
                    << yes(p[0].centre == particles[0].centre) << std::endl;
        }
    }

  std::cout << (testing::all_passed ? "all checks passed" : "FAILED")
            << std::endl;
  return testing::all_passed ? 0 : 1;
}
