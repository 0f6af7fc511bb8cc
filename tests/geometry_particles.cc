// Test of read_particle_csv() and check_particles() and their messages.
#include <deal.II/base/timer.h>

#include <densify/geometry/particles.h>

#include "test_utilities.h"

#include <cstdint>
#include <fstream>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>

using namespace densify;

using densify::testing::all_passed;
using densify::testing::write_file;
using densify::testing::yes;

namespace
{



  /// Read @p name and print the particles or the error message.
  void
  read(const std::string &name, const bool expect_error)
  {
    try
      {
        const std::vector<Particle> particles = read_particle_csv(name, "Cu");
        std::cout << name << ": " << particles.size() << " particles"
                  << std::endl;
        for (unsigned int i = 0; i < particles.size(); ++i)
          std::cout << "  particle " << i << ": centre ("
                    << particles[i].centre[0] << ", " << particles[i].centre[1]
                    << ", " << particles[i].centre[2] << ") diameter "
                    << particles[i].diameter << " material '"
                    << particles[i].material << "'" << std::endl;
        if (expect_error)
          std::cout << "  expected an error: " << yes(false) << std::endl;
      }
    catch (const std::runtime_error &e)
      {
        std::cout << e.what() << std::endl;
        if (!expect_error)
          std::cout << "  unexpected error: " << yes(false) << std::endl;
      }
  }



  /// Run check_particles() and print "ok" or the error message.
  std::string
  check(const std::vector<Particle> &particles,
        const Container             &container,
        const double                 tolerance = 1e-9)
  {
    try
      {
        check_particles(particles, container, tolerance);
        return "ok";
      }
    catch (const std::runtime_error &e)
      {
        return e.what();
      }
  }



  /// Print the outcome of a check and compare it with what is expected.
  void
  report(const std::string           &what,
         const std::vector<Particle> &particles,
         const Container             &container,
         const bool                   expect_ok,
         const double                 tolerance = 1e-9)
  {
    const std::string result = check(particles, container, tolerance);
    std::cout << what << ": " << result << std::endl;
    if ((result == "ok") != expect_ok)
      std::cout << "  unexpected outcome: " << yes(false) << std::endl;
  }



  /// A particle.
  Particle
  particle(const double x, const double y, const double z, const double d)
  {
    Particle p;
    p.centre   = Point<3>(x, y, z);
    p.diameter = d;
    return p;
  }



  /// A uniform random number in [0, 1) from the (portable) mt19937 stream.
  double
  uniform(std::mt19937 &random)
  {
    return random() / 4294967296.;
  }
} // namespace



int
main()
{
  // Reading.
  write_file("good.csv",
             "# particles of the test\n"
             "x, y, z, diameter, material\n"
             "0,0,1.25,2.5,Sn\n"
             "\n"
             "   # an indented comment\n"
             "3.0, 0, 1.25, 2.5\n"
             "0,0,3.75,2.5e0,Fe\r\n"
             "-3,0,1.25,2.0,\n"
             "  1.5e-1 , -2 , 4 , 1 , Sn  \n");
  read("good.csv", false);
  write_file("only-comments.csv", "# nothing here\n\n");
  read("only-comments.csv", false);
  read("no-such-file.csv", true);
  write_file("bad-fields.csv", "x,y,z,d\n0,0,1.25,2.5\n1,2,3\n");
  read("bad-fields.csv", true);
  write_file("six-fields.csv", "0,0,1.25,2.5,Sn,extra\n");
  read("six-fields.csv", true);
  write_file("non-numeric.csv", "# comment\nx,y,z,d\n1,2,abc,2.5\n");
  read("non-numeric.csv", true);
  write_file("empty-field.csv", "1,,3,2.5\n");
  read("empty-field.csv", true);
  write_file("second-header.csv", "x,y,z,d\n0,0,1.25,2.5\nx,y,z,d\n");
  read("second-header.csv", true);
  write_file("trailing-garbage.csv", "0,0,1.25,2.5mm\n");
  read("trailing-garbage.csv", true);

  // Checking: a valid set in a die of radius 10 between z = 0 and z = 10.
  Container container;
  container.has_die    = true;
  container.die_radius = 10.;
  container.has_lower  = true;
  container.lower_z    = 0.;
  container.has_upper  = true;
  container.upper_z    = 10.;

  std::vector<Particle> six;
  for (unsigned int i = 0; i < 6; ++i)
    six.push_back(particle(-7.5 + 3. * i, 0., 1.25, 2.5));
  report("six separate particles", six, container, true);

  std::vector<Particle> overlapping = six;
  overlapping[3].centre             = Point<3>(0., 5., 1.25);
  overlapping[5].centre             = Point<3>(0., 5., 1.25 + 2.4);
  report("particles 3 and 5 overlapping by 0.1", overlapping, container, false);

  std::vector<Particle> pair = {particle(0, 0, 1.25, 2.5),
                                particle(0, 0, 3.75, 2.5)};
  report("touching pole to pole (distance == sum of radii)",
         pair,
         container,
         true);
  pair[1].centre[2] = 3.75 - 5e-10;
  report("overlap 5e-10 < tolerance 1e-9", pair, container, true);
  pair[1].centre[2] = 3.75 - 2e-9;
  report("overlap 2e-9 > tolerance 1e-9", pair, container, false);
  pair[1].centre[2] = 3.75 - 2e-9;
  report("overlap 2e-9 < tolerance 1e-8", pair, container, true, 1e-8);
  pair = {particle(0, 0, 1.25, 2.5), particle(1., 0, 1.25, 0.1)};
  report("small particle inside a big one", pair, container, false);

  std::vector<Particle> bad = six;
  bad[2].diameter           = -1.;
  report("negative diameter", bad, container, false);
  bad[2].diameter = 0.;
  report("zero diameter", bad, container, false);

  std::vector<Particle> outside = six;
  outside[3].centre[0]          = 8.85;
  outside[3].centre[1]          = 0.;
  report("outside the die wall by 0.1", outside, container, false);
  outside[3].centre =
    Point<3>(8.75 / std::sqrt(2.), 8.75 / std::sqrt(2.), 1.25);
  report("touching the die wall at 45 degrees", outside, container, true);

  std::vector<Particle> low = six;
  low[1].centre[2]          = 1.15;
  report("below the lower punch by 0.1", low, container, false);
  low[1].centre[2] = 1.25;
  report("touching the lower punch", low, container, true);

  std::vector<Particle> high = six;
  high[4].centre[2]          = 8.85;
  report("above the upper punch by 0.1", high, container, false);
  high[4].centre[2] = 8.75;
  report("touching the upper punch", high, container, true);

  Container no_walls;
  report("no container, particle far away",
         {particle(100., -50., -1000., 2.5)},
         no_walls,
         true);
  report("empty set", {}, container, true);

  // 4000 particles on a touching cubic lattice (spacing == diameter).
  std::vector<Particle> lattice;
  for (unsigned int i = 0; i < 20; ++i)
    for (unsigned int j = 0; j < 20; ++j)
      for (unsigned int k = 0; k < 10; ++k)
        lattice.push_back(
          particle(-23.75 + 2.5 * i, -23.75 + 2.5 * j, 1.25 + 2.5 * k, 2.5));
  Container big  = container;
  big.die_radius = 40.;
  big.upper_z    = 25.;
  Timer             timer;
  const std::string lattice_result = check(lattice, big);
  timer.stop();
  std::cout << lattice.size()
            << " particles on a touching lattice: " << lattice_result
            << std::endl;
  std::cout << "checked in less than 0.2 s: " << yes(timer.wall_time() < 0.2)
            << std::endl;
  lattice[2345].centre[0] += 0.01;
  std::cout << "one of them moved by 0.01: " << check(lattice, big)
            << std::endl;

  // The cell grid finds the same first pair as comparing every pair.
  std::mt19937 random(42);
  unsigned int agree = 0, n_overlapping = 0;
  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      std::vector<Particle> set;
      for (unsigned int i = 0; i < 40; ++i)
        {
          const double x = 40. * uniform(random);
          const double y = 40. * uniform(random);
          const double z = 40. * uniform(random);
          const double d = 0.5 + 3. * uniform(random);
          set.push_back(particle(x, y, z, d));
        }
      std::string expected = "ok";
      for (unsigned int i = 0; i < set.size() && expected == "ok"; ++i)
        for (unsigned int j = i + 1; j < set.size() && expected == "ok"; ++j)
          if (0.5 * (set[i].diameter + set[j].diameter) -
                set[i].centre.distance(set[j].centre) >
              1e-9)
            expected = "particles " + std::to_string(i) + " and " +
                       std::to_string(j) + " overlap";
      const std::string result = check(set, no_walls);
      if (expected != "ok")
        ++n_overlapping;
      if (result.compare(0, expected.size(), expected) == 0)
        ++agree;
      else
        std::cout << "  trial " << trial << ": expected '" << expected
                  << "', got '" << result << "'" << std::endl;
    }
  std::cout << "cell grid and all-pairs search agree on 200 random sets "
               "(some overlapping, some not): "
            << yes(agree == 200 && n_overlapping > 20 && n_overlapping < 180)
            << std::endl;

  return all_passed ? 0 : 1;
}
