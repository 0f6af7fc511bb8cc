// A bed poured into the die (deposition.h, Particles/Packing = deposited):
// - 600 equal spheres of 1 mm in a 12 mm die: no two overlap (to 1e-9 mm),
//   all inside the die and above the floor, every sphere rests (on the
//   floor, or on three or more of spheres and wall, within 1e-5 of its
//   radius), and the solid fraction
//   of the bulk (2 diameters from the wall, the floor and the top) lies in
//   the poured range 0.55-0.60 (Visscher and Bolsterli's sequential
//   deposition: 0.582), its coordination number near 6 (each sphere rests
//   on three and carries three on average);
// - the same seed gives the same bed, another seed another;
// - a uniform distribution between 0.8 and 1.2 mm stays in its range with
//   its mean; a log-normal one (d50 1 mm, spread 0.2) has its median and
//   stays within three spreads;
// - a fill height: every top below it.
#include <densify/geometry/deposition.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace densify;

namespace
{
  unsigned int failures = 0;

  void
  check(const char *what, const bool ok)
  {
    std::printf("%-60s %s\n", what, ok ? "yes" : "NO");
    failures += ok ? 0 : 1;
  }

  /// No overlaps, inside the die, above the floor; each resting sphere
  /// supported; returns the bed's top.
  double
  check_bed(const std::vector<Particle> &bed, const double R)
  {
    bool   apart = true, inside = true, resting = true;
    double top = 0;
    for (unsigned int i = 0; i < bed.size(); ++i)
      {
        const double    r = bed[i].diameter / 2;
        const Point<3> &c = bed[i].centre;
        top               = std::max(top, c[2] + r);
        inside =
          inside && c[2] >= r - 1e-9 && std::hypot(c[0], c[1]) <= R - r + 1e-9;
        unsigned int supports = 0;
        if (std::hypot(c[0], c[1]) >= R - r - 1e-5 * r)
          ++supports;
        for (unsigned int j = 0; j < bed.size(); ++j)
          if (j != i)
            {
              const double gap =
                (c - bed[j].centre).norm() - r - bed[j].diameter / 2;
              apart = apart && gap >= -1e-9;
              if (gap <= 1e-5 * r)
                ++supports;
            }
        resting = resting && (c[2] <= r + 1e-5 * r || supports >= 3);
      }
    check("  no two spheres overlap", apart);
    check("  all inside the die and above the floor", inside);
    check("  every sphere rests on the floor or on three supports", resting);
    return top;
  }
} // namespace



int
main()
{
  DepositionSpec spec;
  spec.die_diameter               = 12;
  spec.first                      = 1;
  spec.n_particles                = 600;
  spec.seed                       = 1;
  const std::vector<Particle> bed = deposit(spec);
  std::printf("600 equal spheres of 1 mm, die 12 mm:\n");
  const double top  = check_bed(bed, 6.);
  const double bulk = solid_fraction(bed, 6. - 2., 2., top - 2., 80);
  const double z    = mean_coordination(bed);
  // the bulk's spheres: two diameters from the wall, the floor and the top
  double       bulk_contacts = 0;
  unsigned int n_bulk        = 0;
  for (const Particle &p : bed)
    if (std::hypot(p.centre[0], p.centre[1]) <= 4 && p.centre[2] >= 2 &&
        p.centre[2] <= top - 2)
      {
        ++n_bulk;
        for (const Particle &q : bed)
          if (&q != &p && (p.centre - q.centre).norm() - 1 <= 1e-5)
            ++bulk_contacts;
      }
  const double z_bulk = bulk_contacts / n_bulk;
  // the measured numbers to stderr: the compared output holds the checks
  std::fprintf(stderr,
               "  bed height %.1f mm, bulk solid fraction %.2f, mean "
               "coordination %.1f (bulk %.1f)\n",
               top,
               bulk,
               z,
               z_bulk);
  check("  bulk solid fraction in 0.55-0.60", bulk >= 0.55 && bulk <= 0.60);
  check("  the bulk's coordination number within 5.5-6.5 (6 in theory)",
        z_bulk >= 5.5 && z_bulk <= 6.5);

  {
    const std::vector<Particle> again = deposit(spec);
    bool                        same  = again.size() == bed.size();
    for (unsigned int i = 0; same && i < bed.size(); ++i)
      same = again[i].centre == bed[i].centre;
    check("the same seed gives the same bed", same);
    DepositionSpec other = spec;
    other.seed           = 2;
    other.n_particles    = 50;
    check("another seed gives another bed",
          deposit(other)[0].centre != bed[0].centre);
  }

  {
    DepositionSpec uniform        = spec;
    uniform.sizes                 = SizeDistribution::uniform;
    uniform.first                 = 0.8;
    uniform.second                = 1.2;
    uniform.n_particles           = 400;
    const std::vector<Particle> b = deposit(uniform);
    std::printf("400 spheres uniform in 0.8-1.2 mm:\n");
    check_bed(b, 6.);
    double lo = 1e9, hi = 0, mean = 0;
    for (const Particle &p : b)
      {
        lo = std::min(lo, p.diameter);
        hi = std::max(hi, p.diameter);
        mean += p.diameter / b.size();
      }
    check("  diameters within 0.8-1.2 mm, mean within 0.02 of 1 mm",
          lo >= 0.8 && hi <= 1.2 && std::abs(mean - 1) <= 0.02);
  }

  {
    DepositionSpec log_normal     = spec;
    log_normal.sizes              = SizeDistribution::log_normal;
    log_normal.second             = 0.2;
    log_normal.n_particles        = 400;
    const std::vector<Particle> b = deposit(log_normal);
    std::printf("400 spheres log-normal, d50 1 mm, spread 0.2:\n");
    check_bed(b, 6.);
    std::vector<double> d;
    for (const Particle &p : b)
      d.push_back(p.diameter);
    std::sort(d.begin(), d.end());
    const double median = d[d.size() / 2];
    check("  median within 0.03 of 1 mm, all within three spreads",
          std::abs(median - 1) <= 0.03 && d.front() >= std::exp(-0.6) &&
            d.back() <= std::exp(0.6));
  }

  {
    DepositionSpec fill           = spec;
    fill.fill_height              = 3;
    fill.n_particles              = 10000;
    fill.floor                    = 0.5;
    const std::vector<Particle> b = deposit(fill);
    double                      t = 0;
    for (const Particle &p : b)
      t = std::max(t, p.centre[2] + p.diameter / 2);
    std::printf("fill height 3 mm over a floor at 0.5 mm: %s particles\n",
                b.size() > 100 ? "more than 100" : "too few");
    check("  every top below 3.5 mm", t <= 3.5 + 1e-12);
  }
  return failures == 0 ? 0 : 1;
}
