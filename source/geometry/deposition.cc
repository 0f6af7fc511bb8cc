// A powder bed poured into the die by sequential deposition.
#include <deal.II/base/numbers.h>

#include <densify/geometry/deposition.h>
#include <densify/geometry/packing.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// The diameters to pour, in pouring order.
    std::vector<double>
    draw_diameters(const DepositionSpec &spec, std::mt19937 &random)
    {
      const double a = spec.first, b = spec.second;
      const auto   fail = [](const std::string &what) {
        throw std::runtime_error("Particles/Diameters: " + what);
      };
      if (!(a > 0) || !std::isfinite(a))
        fail("the first value must be > 0 mm");
      if (spec.sizes == SizeDistribution::uniform && !(b >= a))
        fail("a uniform distribution needs the smallest and the largest "
             "diameter, 'dmin, dmax' with dmax >= dmin");
      if (spec.sizes == SizeDistribution::log_normal && !(b >= 0 && b <= 1))
        fail("a log-normal distribution needs the median diameter and the "
             "spread of ln d, 'd50, s' with 0 <= s <= 1");
      std::vector<double> d(spec.n_particles);
      for (double &x : d)
        switch (spec.sizes)
          {
            case SizeDistribution::equal:
              x = a;
              break;
            case SizeDistribution::uniform:
              x = a + (b - a) * uniform_random(random);
              break;
            case SizeDistribution::log_normal:
              {
                // Box-Muller, truncated at three spreads
                double z = 0;
                do
                  {
                    const double u1 = 1 - uniform_random(random);
                    const double u2 = uniform_random(random);
                    z               = std::sqrt(-2 * std::log(u1)) *
                        std::cos(2 * numbers::PI * u2);
                } while (std::abs(z) > 3);
                x = a * std::exp(b * z);
                break;
              }
          }
      return d;
    }



    /**
     * The placed spheres in columns of a square grid over the die, to find
     * the neighbours of a point in O(1).
     */
    class Columns
    {
    public:
      Columns(const double half_width, const double cell)
        : half_width(half_width)
        , cell(cell)
        , n(std::max(1, static_cast<int>(std::ceil(2 * half_width / cell))))
        , members(n * n)
      {}

      void
      add(const unsigned int index, const Point<3> &c)
      {
        members[column(c[0]) * n + column(c[1])].push_back(index);
      }

      /// The spheres in the columns within @p reach of (x, y).
      void
      near(const Point<3>            &c,
           const double               reach,
           std::vector<unsigned int> &result) const
      {
        result.clear();
        const int i0 = column(c[0] - reach), i1 = column(c[0] + reach);
        const int j0 = column(c[1] - reach), j1 = column(c[1] + reach);
        for (int i = i0; i <= i1; ++i)
          for (int j = j0; j <= j1; ++j)
            result.insert(result.end(),
                          members[i * n + j].begin(),
                          members[i * n + j].end());
      }

    private:
      int
      column(const double x) const
      {
        return std::clamp(static_cast<int>(std::floor((x + half_width) / cell)),
                          0,
                          n - 1);
      }

      double                                 half_width, cell;
      int                                    n;
      std::vector<std::vector<unsigned int>> members;
    };
  } // namespace



  std::vector<Particle>
  deposit(const DepositionSpec &spec)
  {
    const double R = spec.die_diameter / 2;
    if (!(R > 0) || !std::isfinite(R))
      throw std::runtime_error("Tools/Die wall/Diameter must be > 0 mm");
    std::mt19937              random(spec.seed);
    const std::vector<double> diameters = draw_diameters(spec, random);
    double d_min = std::numeric_limits<double>::max(), d_max = 0;
    for (const double d : diameters)
      {
        d_min = std::min(d_min, d);
        d_max = std::max(d_max, d);
      }
    if (d_max >= spec.die_diameter)
      {
        std::ostringstream message;
        message << std::setprecision(6) << "Particles/Diameters: a sphere of "
                << d_max << " mm does not fit the die of " << spec.die_diameter
                << " mm (Tools/Die wall/Diameter)";
        throw std::runtime_error(message.str());
      }

    std::vector<Particle>     placed;
    Columns                   columns(R, d_max);
    std::vector<unsigned int> candidates;
    double                    bed_top = spec.floor;

    // move c onto the constraints of a sphere of radius r (floor, wall,
    // the candidates) by Newton's method on the violated ones: the least
    // change that closes their linearised overlaps (the three largest at a
    // time); false if that does not converge
    const auto project = [&](Point<3> &c, const double r) {
      for (unsigned int it = 0; it < 30; ++it)
        {
          columns.near(c, r + d_max / 2, candidates);
          // (overlap, outward normal) of each violated constraint
          std::vector<std::pair<double, Tensor<1, 3>>> violated;
          if (c[2] < spec.floor + r)
            violated.emplace_back(spec.floor + r - c[2],
                                  Tensor<1, 3>({0., 0., 1.}));
          const double rho = std::hypot(c[0], c[1]);
          if (rho > R - r)
            violated.emplace_back(rho - (R - r),
                                  Tensor<1, 3>({-c[0] / rho, -c[1] / rho, 0.}));
          for (const unsigned int j : candidates)
            {
              const Tensor<1, 3> d    = c - placed[j].centre;
              const double       need = r + placed[j].diameter / 2;
              const double       dist = d.norm();
              if (dist < need)
                violated.emplace_back(need - dist,
                                      dist > 0 ? Tensor<1, 3>(d / dist) :
                                                 Tensor<1, 3>({0., 0., 1.}));
            }
          if (violated.empty())
            return true;
          std::sort(violated.begin(),
                    violated.end(),
                    [](const auto &a, const auto &b) {
                      return a.first > b.first;
                    });
          if (violated[0].first <= 1e-13 * r)
            return true;
          const unsigned int m = std::min<std::size_t>(3, violated.size());
          // G l = v with G = N^T N, then c += N l (Gauss-Jordan on m <= 3)
          double G[3][4];
          for (unsigned int a = 0; a < m; ++a)
            {
              for (unsigned int b = 0; b < m; ++b)
                G[a][b] = violated[a].second * violated[b].second +
                          (a == b ? 1e-12 : 0.);
              G[a][3] = violated[a].first;
            }
          for (unsigned int a = 0; a < m; ++a)
            for (unsigned int b = 0; b < m; ++b)
              if (b != a)
                {
                  const double f = G[b][a] / G[a][a];
                  for (unsigned int e = a; e < 4; ++e)
                    G[b][e] -= f * G[a][e];
                }
          for (unsigned int a = 0; a < m; ++a)
            c += (G[a][3] / G[a][a]) * violated[a].second;
        }
      return false;
    };

    // the direction of steepest descent of the height at c among the
    // directions the touching constraints allow: gravity (0, 0, -1) minus
    // its components into the supports, d = g + sum_s l_s n_s with l_s >=
    // 0 over a subset S of the touching constraints' outward normals and
    // n.d >= 0 for all of them (the projection of g onto their tangent
    // cone, found by trying the subsets of up to two; three independent
    // supports hold the sphere: d = 0)
    const auto descent = [&](const Point<3> &c, const double r) {
      const double              touch = 1e-5 * r;
      std::vector<Tensor<1, 3>> n;
      if (c[2] - r - spec.floor <= touch)
        n.push_back(Tensor<1, 3>({0., 0., 1.}));
      const double rho = std::hypot(c[0], c[1]);
      if (rho > 0 && R - r - rho <= touch)
        n.push_back(Tensor<1, 3>({-c[0] / rho, -c[1] / rho, 0.}));
      for (const unsigned int j : candidates)
        {
          const Tensor<1, 3> a = c - placed[j].centre;
          if (a.norm() - r - placed[j].diameter / 2 <= touch)
            n.push_back(a / a.norm());
        }
      const Tensor<1, 3> g({0., 0., -1.});
      const auto         admissible = [&](const Tensor<1, 3> &d) {
        for (const Tensor<1, 3> &m : n)
          if (m * d < -1e-12)
            return false;
        return true;
      };
      if (admissible(g))
        return g;
      Tensor<1, 3> best;
      double       best_descent = 0;
      const auto   consider     = [&](const Tensor<1, 3> &d) {
        if (-d[2] > best_descent + 1e-15 && admissible(d))
          {
            best         = d;
            best_descent = -d[2];
          }
      };
      for (unsigned int a = 0; a < n.size(); ++a)
        {
          // one support: g minus its normal component, if it pushes
          const double l = -(g * n[a]);
          if (l > 0)
            consider(g + l * n[a]);
          for (unsigned int b = a + 1; b < n.size(); ++b)
            {
              // two supports: g along the line both allow, t = n_a x n_b
              Tensor<1, 3> t = cross_product_3d(n[a], n[b]);
              if (t.norm() < 1e-12)
                continue;
              t /= t.norm();
              const Tensor<1, 3> d = (g * t) * t;
              // multipliers of g - d = -(l_a n_a + l_b n_b) >= 0
              const Tensor<1, 3> w   = d - g;
              const double       ab  = n[a] * n[b];
              const double       det = 1 - ab * ab;
              const double       la  = ((w * n[a]) - ab * (w * n[b])) / det;
              const double       lb  = ((w * n[b]) - ab * (w * n[a])) / det;
              if (la >= -1e-12 && lb >= -1e-12)
                consider(d);
            }
        }
      // resting on exactly two supports other than the floor, with gravity
      // in their plane, is the top of the circle the sphere can roll along
      // while it touches both: an unstable equilibrium; roll off it along
      // that circle (a level first step, then down)
      if (best_descent == 0 && n.size() == 2 && n[0][2] != 1.)
        {
          const Tensor<1, 3> t = cross_product_3d(n[0], n[1]);
          if (t.norm() > 1e-12)
            return Tensor<1, 3>(t / t.norm());
        }
      return best;
    };

    for (unsigned int k = 0; k < diameters.size(); ++k)
      {
        const double r = diameters[k] / 2;
        // a drop position over the floor where the sphere fits the die
        Point<3> c;
        do
          {
            c[0] = (R - r) * (2 * uniform_random(random) - 1);
            c[1] = (R - r) * (2 * uniform_random(random) - 1);
        } while (std::hypot(c[0], c[1]) > R - r);
        c[2] = bed_top + r;
        // steps no longer than the smallest radius: no sphere passes
        // through another
        const double longest = 0.5 * std::min(r, d_min / 2);
        double       h       = longest;
        columns.near(c, r + d_max / 2 + longest, candidates);
        if (!project(c, r))
          throw std::runtime_error(
            "Particles/Packing = deposited: a sphere could not be placed "
            "above the bed (Particles/Packing seed " +
            std::to_string(spec.seed) + ")");
        // (the cap on the iterations only guards the loop: the spheres of
        // the test's beds come to rest within ten thousand)
        for (unsigned int it = 0; it < 100000 && h > 1e-10 * r; ++it)
          {
            columns.near(c, r + d_max / 2 + 2 * h, candidates);
            const Tensor<1, 3> d = descent(c, r);
            if (d.norm() < 1e-9)
              break; // gravity balanced by the supports: at rest
            Point<3> trial = c + h * d / d.norm();
            // a step counts if it lowers the sphere by a tenth of what the
            // direction promises; otherwise (a new contact on the way, the
            // curvature of a support) the step is refined
            if (project(trial, r) &&
                c[2] - trial[2] >= 0.1 * h * -d[2] / d.norm())
              {
                c = trial;
                h = std::min(2 * h, longest);
              }
            else
              h /= 2;
          }
        if (spec.fill_height > 0 && c[2] + r > spec.floor + spec.fill_height)
          break;
        Particle p;
        p.centre   = c;
        p.diameter = diameters[k];
        p.material = spec.material;
        columns.add(placed.size(), c);
        placed.push_back(p);
        bed_top = std::max(bed_top, c[2] + r);
      }
    return placed;
  }



  double
  mean_coordination(const std::vector<Particle> &particles,
                    const double                 tolerance)
  {
    if (particles.empty())
      return 0;
    double d_max = 0;
    for (const Particle &p : particles)
      d_max = std::max(d_max, p.diameter);
    // spheres in contact lie in the same or in neighbouring slices of
    // height d_max
    std::map<long, std::vector<unsigned int>> layers;
    for (unsigned int i = 0; i < particles.size(); ++i)
      layers[static_cast<long>(std::floor(particles[i].centre[2] / d_max))]
        .push_back(i);
    unsigned long pairs = 0;
    for (const auto &[layer, members] : layers)
      for (const long other : {layer, layer + 1})
        {
          const auto it = layers.find(other);
          if (it == layers.end())
            continue;
          for (const unsigned int i : members)
            for (const unsigned int j : it->second)
              if (other != layer || j > i)
                {
                  const Particle &a = particles[i], &b = particles[j];
                  const double    gap = (a.centre - b.centre).norm() -
                                     (a.diameter + b.diameter) / 2;
                  if (gap <= tolerance * std::min(a.diameter, b.diameter))
                    ++pairs;
                }
        }
    return 2. * pairs / particles.size();
  }



  double
  solid_fraction(const std::vector<Particle> &particles,
                 const double                 radius,
                 const double                 bottom,
                 const double                 top,
                 const unsigned int           n)
  {
    const double  h      = 2 * radius / n;
    unsigned long inside = 0, total = 0;
    for (double z = bottom + h / 2; z < top; z += h)
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
          {
            const Point<3> x(-radius + (i + 0.5) * h,
                             -radius + (j + 0.5) * h,
                             z);
            if (x[0] * x[0] + x[1] * x[1] > radius * radius)
              continue;
            ++total;
            for (const Particle &p : particles)
              if ((x - p.centre).norm_square() <= p.diameter * p.diameter / 4)
                {
                  ++inside;
                  break;
                }
          }
    return total > 0 ? double(inside) / total : 0.;
  }
} // namespace densify
