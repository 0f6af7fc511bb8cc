// Test of hexagonal_layer(), random_layer() and layer_relative_density().
#include <densify/geometry/packing.h>
#include <densify/geometry/particles.h>

#include "test_utilities.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace densify;

using densify::testing::all_passed;
using densify::testing::yes;

namespace
{



  /// The reference die: radius 10 mm, punches at z = 0 and z = 2.5 mm.
  Container
  reference_die()
  {
    Container container;
    container.has_die    = true;
    container.die_radius = 10.;
    container.has_lower  = true;
    container.lower_z    = 0.;
    container.has_upper  = true;
    container.upper_z    = 2.5;
    return container;
  }



  /// Run check_particles() on the reference die: "ok" or the message.
  std::string
  check(const std::vector<Particle> &particles)
  {
    try
      {
        check_particles(particles, reference_die(), 1e-9);
        return "ok";
      }
    catch (const std::runtime_error &e)
      {
        all_passed = false;
        return e.what();
      }
  }



  /// Relative density in percent, 4 significant digits.
  std::string
  percent(const std::vector<Particle> &particles)
  {
    std::ostringstream s;
    s << std::fixed << std::setprecision(2)
      << 100. * layer_relative_density(particles, 20., 2.5) << " %";
    return s.str();
  }



  /// Sum of the distances of the centres from the axis, 6 digits.
  std::string
  checksum(const std::vector<Particle> &particles)
  {
    double sum = 0.;
    for (const Particle &p : particles)
      sum += std::hypot(p.centre[0], p.centre[1]);
    std::ostringstream s;
    s << std::setprecision(6) << sum;
    return s.str();
  }



  /// Same centres, diameters and materials, bit for bit?
  bool
  identical(const std::vector<Particle> &a, const std::vector<Particle> &b)
  {
    if (a.size() != b.size())
      return false;
    for (unsigned int i = 0; i < a.size(); ++i)
      if (a[i].centre != b[i].centre || a[i].diameter != b[i].diameter ||
          a[i].material != b[i].material)
        return false;
    return true;
  }



  /// The number of particles that touch another one (gap < 1e-9 mm).
  unsigned int
  n_touching(const std::vector<Particle> &particles)
  {
    unsigned int n = 0;
    for (unsigned int i = 0; i < particles.size(); ++i)
      for (unsigned int j = 0; j < particles.size(); ++j)
        if (j != i &&
            particles[i].centre.distance(particles[j].centre) -
                0.5 * (particles[i].diameter + particles[j].diameter) <
              1e-9)
          {
            ++n;
            break;
          }
    return n;
  }



  /// Print what random_layer() says for the given count and diameter.
  void
  expect_error(const double particle_diameter, const unsigned int n_particles)
  {
    try
      {
        random_layer(20., particle_diameter, 1.25, n_particles, 1, "Sn");
        std::cout << "  expected an error: " << yes(false) << std::endl;
      }
    catch (const std::runtime_error &e)
      {
        std::cout << e.what() << std::endl;
      }
  }
} // namespace



int
main()
{
  // Hexagonal layers of the reference scene.
  const std::vector<std::pair<std::string, HexagonalPlacement>> placements = {
    {"particle-centred", HexagonalPlacement::particle_centred},
    {"hole-centred", HexagonalPlacement::hole_centred},
    {"edge-centred", HexagonalPlacement::edge_centred},
    {"best", HexagonalPlacement::best}};
  for (const auto &[name, placement] : placements)
    {
      const std::vector<Particle> layer =
        hexagonal_layer(20., 2.5, 1.25, "Sn", 0., placement);
      std::cout << "hexagonal " << name << ": " << layer.size()
                << " particles, density " << percent(layer) << ", check "
                << check(layer) << ", touching " << n_touching(layer)
                << std::endl;
    }
  const std::vector<Particle> paper = hexagonal_layer(
    20., 2.5, 1.25, "Sn", 0., HexagonalPlacement::particle_centred);
  std::cout << "paper scene has 43 particles: " << yes(paper.size() == 43)
            << ", density 44.79 %: "
            << yes(std::abs(layer_relative_density(paper, 20., 2.5) - 0.4479) <
                   5e-5)
            << ", material Sn: " << yes(paper[0].material == "Sn")
            << ", z 1.25: " << yes(paper[0].centre[2] == 1.25) << std::endl;
  std::cout << "best placement has at least as many: "
            << yes(hexagonal_layer(20., 2.5, 1.25, "Sn").size() >= 43)
            << std::endl;
  for (const double clearance : {0.1, 0.5})
    {
      const std::vector<Particle> layer =
        hexagonal_layer(20., 2.5, 1.25, "Sn", clearance);
      double max_edge = 0.;
      for (const Particle &p : layer)
        max_edge =
          std::max(max_edge,
                   std::hypot(p.centre[0], p.centre[1]) + 0.5 * p.diameter);
      std::cout << "hexagonal best, clearance " << clearance << ": "
                << layer.size() << " particles, within 10 - clearance: "
                << yes(max_edge <= 10. - clearance + 1e-9) << std::endl;
    }

  // Random layers (a different seed: the next one).
  // 40 particles (41.67 %) need the relaxation; seed 1 does not reach them
  // within the default number of attempts (38 placed), seeds 2 to 5 do.
  const std::vector<std::pair<unsigned int, unsigned int>> cases = {
    {30, 1}, {30, 2}, {30, 3}, {40, 2}, {40, 3}};
  for (const auto &[n, seed] : cases)
    {
      const std::vector<Particle> layer =
        random_layer(20., 2.5, 1.25, n, seed, "Sn");
      const std::vector<Particle> again =
        random_layer(20., 2.5, 1.25, n, seed, "Sn");
      const std::vector<Particle> other =
        random_layer(20., 2.5, 1.25, n, seed + 1, "Sn");
      std::cout << "random " << n << " seed " << seed << ": " << layer.size()
                << " particles, density " << percent(layer) << ", check "
                << check(layer) << ", deterministic "
                << yes(identical(layer, again)) << ", other seed differs "
                << yes(!identical(layer, other)) << ", checksum "
                << checksum(layer) << std::endl;
    }

  // Errors.
  expect_error(2.5, 60);
  expect_error(25., 1);

  std::cout << (all_passed ? "all passed" : "FAILED") << std::endl;
  return all_passed ? 0 : 1;
}
