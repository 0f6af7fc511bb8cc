// Timing of the broad-phase contact search (cell grid) against the brute
// force for about 40, 400 and 4000 spheres; see README_search.md.
#include <densify/contact/broad_search.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

using namespace densify;

namespace
{
  /// Particle diameter (mm).
  constexpr double diameter = 2.5;

  /// Search margin (mm).
  constexpr double margin = 0.05 * diameter;

  /// A uniform number in [0, 1) from the raw output of @p rng.
  double
  uniform(std::mt19937 &rng)
  {
    return rng() / 4294967296.;
  }



  /// A dense single layer: a hexagonal lattice of touching spheres on the
  /// lower punch (z = d/2) inside the smallest die radius (in steps of
  /// 0.05 mm) that holds at least @p n spheres.
  std::vector<Particle>
  dense_layer(const unsigned int n)
  {
    for (double radius = diameter;; radius += 0.05)
      {
        std::vector<Particle> particles;
        const double          row = diameter * std::sqrt(3.) / 2.;
        const int             m   = static_cast<int>(radius / row) + 2;
        for (int r = -m; r <= m; ++r)
          for (int i = -m; i <= m; ++i)
            {
              Particle p;
              p.diameter  = diameter;
              p.centre[0] = diameter * i + 0.5 * diameter * (r & 1);
              p.centre[1] = row * r;
              p.centre[2] = 0.5 * diameter;
              if (std::hypot(p.centre[0], p.centre[1]) + 0.5 * diameter <=
                  radius)
                particles.push_back(p);
            }
        if (particles.size() >= n)
          return particles;
      }
  }



  /// A 3D random packing: random sequential addition of non-overlapping
  /// spheres into a die of height = its diameter, sized for a solid fraction
  /// of 0.3 with @p n spheres; the die is enlarged by 5% and the filling
  /// restarted while the addition gets stuck (small dies, wall effects).
  std::vector<Particle>
  random_packing(const unsigned int n)
  {
    const double solid  = n * M_PI / 6. * std::pow(diameter, 3);
    double       radius = std::cbrt(solid / 0.3 / (2. * M_PI));
    std::mt19937 rng(42);
    for (;; radius *= 1.05)
      {
        const double          r_max  = radius - 0.5 * diameter;
        const double          height = 2. * radius;
        std::vector<Particle> particles;
        for (unsigned long attempt = 0;
             particles.size() < n && attempt < 1000ul * n;
             ++attempt)
          {
            const double r   = r_max * std::sqrt(uniform(rng));
            const double phi = 2. * M_PI * uniform(rng);
            Particle     p;
            p.diameter = diameter;
            p.centre =
              Point<3>(r * std::cos(phi),
                       r * std::sin(phi),
                       0.5 * diameter + (height - diameter) * uniform(rng));
            bool free = true;
            for (const Particle &q : particles)
              if (p.centre.distance_square(q.centre) < diameter * diameter)
                {
                  free = false;
                  break;
                }
            if (free)
              particles.push_back(p);
          }
        if (particles.size() == n)
          {
            std::printf("# random 3D, N = %u: die radius %.2f mm, solid "
                        "fraction %.3f\n",
                        n,
                        radius,
                        solid / (M_PI * radius * radius * height));
            return particles;
          }
      }
  }



  /// Median wall time (microseconds) of @p repetitions calls of @p f.
  double
  median_time(const std::function<void()> &f, const unsigned int repetitions)
  {
    std::vector<double> times;
    for (unsigned int r = 0; r < repetitions; ++r)
      {
        const auto start = std::chrono::steady_clock::now();
        f();
        const auto end = std::chrono::steady_clock::now();
        times.push_back(
          std::chrono::duration<double, std::micro>(end - start).count());
      }
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
  }



  /// Time one particle set and print its table row.
  bool
  run(const std::string &name, const std::vector<Particle> &particles)
  {
    const auto         boxes = bounding_boxes(particles);
    const auto         grid  = find_candidate_pairs(boxes, margin);
    const auto         brute = find_candidate_pairs_brute_force(boxes, margin);
    std::size_t        sink  = 0;
    const unsigned int repetitions = 21;

    const double t_grid =
      median_time([&]() { sink += find_candidate_pairs(boxes, margin).size(); },
                  repetitions);
    BroadSearch  search;
    const double t_reused =
      median_time([&]() { sink += search.update(boxes, margin).size(); },
                  repetitions);
    const double t_brute = median_time(
      [&]() { sink += find_candidate_pairs_brute_force(boxes, margin).size(); },
      repetitions);

    std::printf("%-14s %6zu %7zu %12.1f %12.1f %12.1f %8s\n",
                name.c_str(),
                boxes.size(),
                grid.size(),
                t_grid,
                t_reused,
                t_brute,
                grid == brute ? "yes" : "NO");
    return grid == brute && sink > 0;
  }
} // namespace



int
main()
{
  std::printf("Broad search, spheres d = %g mm, margin %g mm, median of 21 "
              "runs (microseconds)\n",
              diameter,
              margin);
  std::printf("%-14s %6s %7s %12s %12s %12s %8s\n",
              "set",
              "N",
              "pairs",
              "grid",
              "grid reused",
              "brute force",
              "same");
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  bool ok = true;
  for (const unsigned int n : {40u, 400u, 4000u})
    ok = run("dense layer", dense_layer(n)) && ok;
  for (const unsigned int n : {40u, 400u, 4000u})
    ok = run("random 3D", random_packing(n)) && ok;
  return ok ? 0 : 1;
}
