// Test of the broad-phase contact search (find_candidate_pairs, BroadSearch)
// against the brute force: random sphere sets, touching lattices, degenerate
// inputs.
#include <densify/contact/broad_search.h>

#include "test_utilities.h"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace densify;

using densify::testing::all_passed;
using densify::testing::yes;

namespace
{



  /// A uniform number in [0, 1) from the raw 32-bit output of @p rng (the
  /// standard distributions differ between libraries, mt19937 does not).
  double
  uniform(std::mt19937 &rng)
  {
    return rng() / 4294967296.;
  }



  /// Is each pair (i < j) sorted lexicographically and listed once?
  bool
  well_formed(const std::vector<CandidatePair> &pairs)
  {
    for (unsigned int k = 0; k < pairs.size(); ++k)
      {
        if (pairs[k].first >= pairs[k].second)
          return false;
        if (k > 0 && !(pairs[k - 1] < pairs[k]))
          return false;
      }
    return true;
  }



  /// Run the grid search on @p boxes, compare with the brute force, print
  /// the pair count under @p label and return it.
  std::size_t
  check(const std::string                 &label,
        const std::vector<BoundingBox<3>> &boxes,
        const double                       margin)
  {
    const auto grid  = find_candidate_pairs(boxes, margin);
    const auto brute = find_candidate_pairs_brute_force(boxes, margin);
    std::cout << label << ": " << boxes.size() << " boxes, margin " << margin
              << ": " << grid.size() << " pairs, same as brute force "
              << yes(grid == brute && well_formed(grid)) << std::endl;
    return grid.size();
  }



  /// Spheres of diameter @p diameter at the given centres.
  std::vector<Particle>
  spheres(const std::vector<Point<3>> &centres, const double diameter)
  {
    std::vector<Particle> particles(centres.size());
    for (unsigned int i = 0; i < centres.size(); ++i)
      {
        particles[i].centre   = centres[i];
        particles[i].diameter = diameter;
      }
    return particles;
  }



  /// @p n random spheres, diameters uniform in [2, 3] mm, centres uniform in
  /// a cube sized for the solid volume fraction @p phi (overlaps allowed).
  std::vector<Particle>
  random_spheres(const unsigned int n, const double phi, const unsigned seed)
  {
    std::mt19937          rng(seed);
    std::vector<Particle> particles(n);
    double                volume = 0.;
    for (Particle &p : particles)
      {
        p.diameter = 2. + uniform(rng);
        volume += M_PI / 6. * std::pow(p.diameter, 3);
      }
    const double side = std::cbrt(volume / phi);
    for (Particle &p : particles)
      for (unsigned int d = 0; d < 3; ++d)
        p.centre[d] = side * uniform(rng);
    return particles;
  }



  /// The error message of find_candidate_pairs(), or "no exception".
  std::string
  error_of(const std::vector<BoundingBox<3>> &boxes, const double margin)
  {
    try
      {
        find_candidate_pairs(boxes, margin);
      }
    catch (const std::runtime_error &e)
      {
        return e.what();
      }
    return "no exception";
  }
} // namespace



int
main()
{
  // Degenerate inputs.
  std::cout << "Degenerate inputs" << std::endl;
  check("no boxes", {}, 0.);
  check("one box", bounding_boxes(spheres({Point<3>(1, 2, 3)}, 2.5)), 0.1);
  check("two equal boxes",
        bounding_boxes(spheres({Point<3>(), Point<3>()}, 1.)),
        0.);
  {
    // 100 coincident points (zero extent, margin 0): all pairs, all in one
    // cell.
    check("coincident points",
          bounding_boxes(
            spheres(std::vector<Point<3>>(100, Point<3>(1, 1, 1)), 0.)),
          0.);
    // 1000 points on 10 distinct locations: pairs only at equal locations.
    std::mt19937          rng(7);
    std::vector<Point<3>> points(1000);
    for (Point<3> &p : points)
      p = Point<3>(static_cast<double>(rng() % 10), 0.5, 0.);
    check("points on 10 locations", bounding_boxes(spheres(points, 0.)), 0.);
    // 100 spheres with centres within one diameter: every pair, one cell.
    std::vector<Point<3>> close(100);
    for (Point<3> &p : close)
      p = Point<3>(uniform(rng), uniform(rng), uniform(rng));
    const std::size_t n_pairs =
      check("one cell", bounding_boxes(spheres(close, 2.5)), 0.);
    std::cout << "  all 4950 pairs: " << yes(n_pairs == 4950) << std::endl;
  }
  std::cout << "bad margin: "
            << error_of(bounding_boxes(spheres({Point<3>()}, 1.)), -1.)
            << std::endl;
  std::cout << "inverted box: "
            << error_of({BoundingBox<3>(),
                         BoundingBox<3>(std::make_pair(Point<3>(0, 0, 1),
                                                       Point<3>(1, 1, 0)))},
                        0.)
            << std::endl;
  std::cout << "infinite box: "
            << error_of({BoundingBox<3>(std::make_pair(
                          Point<3>(0, 0, 0), Point<3>(INFINITY, 1, 1)))},
                        0.)
            << std::endl;

  // Touching lattices (dyadic coordinates, so that distance = diameter is
  // exact): touching boxes must be found with margin 0.
  std::cout << "Touching lattices" << std::endl;
  {
    std::vector<Point<3>> chain;
    for (unsigned int i = 0; i < 20; ++i)
      chain.emplace_back(0.5 * i, 0.25, -0.75);
    const std::size_t n_chain =
      check("chain d = 0.5", bounding_boxes(spheres(chain, 0.5)), 0.);
    std::cout << "  19 pairs: " << yes(n_chain == 19) << std::endl;

    // Simple cubic 5 x 5 x 5, spacing 2.5 = d: each sphere's box touches
    // the boxes of all 26 neighbours, ((3n - 2)^3 - n^3) / 2 = 1036 pairs.
    const unsigned int n = 5;
    for (const double spacing : {2.5, 2.625})
      {
        std::vector<Point<3>> cubic;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            for (unsigned int k = 0; k < n; ++k)
              cubic.emplace_back(spacing * i - 3., spacing * j, spacing * k);
        const auto        boxes = bounding_boxes(spheres(cubic, 2.5));
        const std::string label =
          "cubic spacing " + std::to_string(spacing).substr(0, 5);
        const std::size_t touching = check(label, boxes, 0.);
        const std::size_t gap_half = check(label, boxes, 0.0625);
        const std::size_t gap_full = check(label, boxes, 0.125);
        if (spacing == 2.5)
          std::cout << "  1036 pairs with margin 0: " << yes(touching == 1036)
                    << std::endl;
        else
          std::cout << "  none with margin 0 and 0.0625, 1036 with 0.125: "
                    << yes(touching == 0 && gap_half == 0 && gap_full == 1036)
                    << std::endl;
      }

    // Hexagonal layer, d = 2.5 (rows sqrt(3)/2 d apart, x dyadic): the box
    // pairs are the touching neighbours, 3 m n - 2 (m + n) + 1 for m rows
    // of n spheres.
    const unsigned int    rows = 8, per_row = 12;
    std::vector<Point<3>> hex;
    for (unsigned int r = 0; r < rows; ++r)
      for (unsigned int i = 0; i < per_row; ++i)
        hex.emplace_back(2.5 * i + 1.25 * (r % 2),
                         2.5 * std::sqrt(3.) / 2. * r,
                         1.25);
    const std::size_t n_hex =
      check("hexagonal layer", bounding_boxes(spheres(hex, 2.5)), 0.);
    std::cout << "  " << 3 * rows * per_row - 2 * (rows + per_row) + 1
              << " pairs: "
              << yes(n_hex == 3 * rows * per_row - 2 * (rows + per_row) + 1)
              << std::endl;
  }

  // Random sphere sets at several solid fractions and margins.
  std::cout << "Random spheres" << std::endl;
  {
    unsigned int seed = 1;
    for (const unsigned int n : {10u, 100u, 1000u})
      for (const double phi : {0.01, 0.1, 0.3, 0.6})
        {
          const auto boxes = bounding_boxes(random_spheres(n, phi, seed++));
          for (const double margin : {0., 0.25})
            check("n " + std::to_string(n) + " phi " +
                    std::to_string(phi).substr(0, 4),
                  boxes,
                  margin);
        }
  }

  // Very different sizes: 1000 small spheres and one huge one in the
  // middle, and 100 spheres with one far away.
  std::cout << "Size spread and outliers" << std::endl;
  {
    std::vector<Particle> particles = random_spheres(1000, 0.2, 99);
    for (Particle &p : particles)
      p.diameter *= 0.05;
    Particle big;
    big.centre   = Point<3>(15, 15, 15);
    big.diameter = 30.;
    particles.push_back(big);
    check("one huge sphere", bounding_boxes(particles), 0.01);

    std::vector<Particle> far = random_spheres(100, 0.3, 100);
    Particle              outlier;
    outlier.centre   = Point<3>(1e12, -3e11, 5.);
    outlier.diameter = 2.5;
    far.push_back(outlier);
    far.push_back(outlier);
    check("far outliers", bounding_boxes(far), 0.1);
  }

  // Refreshing one BroadSearch as the particles move.
  std::cout << "Moving particles" << std::endl;
  {
    std::mt19937          rng(2024);
    std::vector<Particle> particles = random_spheres(1000, 0.3, 5);
    BroadSearch           search;
    for (unsigned int step = 0; step < 5; ++step)
      {
        const auto  boxes = bounding_boxes(particles);
        const auto &grid  = search.update(boxes, 0.1);
        const auto  brute = find_candidate_pairs_brute_force(boxes, 0.1);
        std::cout << "step " << step << ": " << grid.size()
                  << " pairs, same as brute force "
                  << yes(grid == brute && search.pairs() == brute) << std::endl;
        // Shrink towards the origin by 10% and jiggle.
        for (Particle &p : particles)
          for (unsigned int d = 0; d < 3; ++d)
            p.centre[d] = 0.9 * p.centre[d] + 0.5 * (uniform(rng) - 0.5);
      }
    // Fewer boxes after more: the work arrays are resized correctly.
    particles.resize(10);
    const auto boxes = bounding_boxes(particles);
    std::cout << "10 particles after 1000: same as brute force "
              << yes(search.update(boxes, 0.1) ==
                     find_candidate_pairs_brute_force(boxes, 0.1))
              << std::endl;
  }

  std::cout << (all_passed ? "All checks passed" : "SOME CHECKS FAILED")
            << std::endl;
  return all_passed ? 0 : 1;
}
