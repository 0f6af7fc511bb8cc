// Single layers of equal spheres in a die: hexagonal lattice and random.
#include <deal.II/base/numbers.h>

#include <densify/geometry/packing.h>
#include <densify/geometry/particle_shape.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// A number with at most 6 significant digits, for messages.
    std::string
    fmt(const double x)
    {
      std::ostringstream s;
      s.precision(6);
      s << x;
      return s.str();
    }



    /// Throw std::runtime_error unless @p value is finite and > 0.
    void
    require_positive(const std::string &function,
                     const std::string &what,
                     const double       value)
    {
      if (!(value > 0.) || !std::isfinite(value))
        throw std::runtime_error(function + ": " + what + " " + fmt(value) +
                                 " mm must be > 0");
    }



    /**
     * A triangular lattice of spacing d clipped to the disc |x| <= rho: the
     * lattice points are (ox, oy) + i (d, 0) + j (d/2, d sqrt(3)/2).
     */
    struct ClippedLattice
    {
      /// Lattice spacing.
      double d;
      /// x of the lattice point (0, 0).
      double ox;
      /// y of the lattice point (0, 0).
      double oy;
      /// Radius of the disc of admissible points.
      double rho;

      /// Row spacing.
      double
      h() const
      {
        return 0.5 * std::sqrt(3.) * d;
      }

      /// The range of rows j with a y coordinate in [-rho, rho].
      std::pair<long, long>
      rows() const
      {
        return {static_cast<long>(std::ceil((-rho - oy) / h())),
                static_cast<long>(std::floor((rho - oy) / h()))};
      }

      /// The range of columns i of row @p j inside the disc (empty if
      /// first > last).
      std::pair<long, long>
      columns(const long j) const
      {
        const double y  = oy + j * h();
        const double w2 = rho * rho - y * y;
        if (w2 < 0.)
          return {1, 0};
        const double w  = std::sqrt(w2);
        const double x0 = ox + 0.5 * j * d;
        return {static_cast<long>(std::ceil((-w - x0) / d)),
                static_cast<long>(std::floor((w - x0) / d))};
      }

      /// The number of lattice points in the disc.
      unsigned long
      count() const
      {
        if (rho < 0.)
          return 0;
        unsigned long n     = 0;
        const auto [j0, j1] = rows();
        for (long j = j0; j <= j1; ++j)
          {
            const auto [i0, i1] = columns(j);
            if (i1 >= i0)
              n += static_cast<unsigned long>(i1 - i0 + 1);
          }
        return n;
      }

      /// The lattice points in the disc, by row, then by x.
      std::vector<std::array<double, 2>>
      points() const
      {
        std::vector<std::array<double, 2>> result;
        if (rho < 0.)
          return result;
        const auto [j0, j1] = rows();
        for (long j = j0; j <= j1; ++j)
          {
            const auto [i0, i1] = columns(j);
            for (long i = i0; i <= i1; ++i)
              result.push_back({{ox + (i + 0.5 * j) * d, oy + j * h()}});
          }
        return result;
      }
    };



    /// The lattice with offset (u, v) in lattice coordinates.
    ClippedLattice
    lattice_at(const double d, const double rho, const double u, const double v)
    {
      return {d, d * (u + 0.5 * v), 0.5 * std::sqrt(3.) * d * v, rho};
    }



    /**
     * A uniform grid of square cells over [-half_width, half_width]^2 that
     * stores particle indices, to find the particles near a point in O(1).
     * Points outside are put in the nearest boundary cell.
     */
    class CellGrid
    {
    public:
      /// A grid of cells of size at least @p cell_size.
      CellGrid(const double half_width, const double cell_size)
        : half_width(half_width)
        , n(static_cast<int>(
            std::clamp(std::floor(2. * half_width / cell_size), 1., 2048.)))
        , size(2. * half_width / n)
        , cells(static_cast<std::size_t>(n) * n)
      {}

      /// Add particle @p i at (x, y).
      void
      insert(const unsigned int i, const double x, const double y)
      {
        cells[index(cell(x), cell(y))].push_back(i);
      }

      /// Remove particle @p i, stored at (x, y).
      void
      remove(const unsigned int i, const double x, const double y)
      {
        auto &c = cells[index(cell(x), cell(y))];
        c.erase(std::find(c.begin(), c.end(), i));
      }

      /// Call @p f(j) for every particle j in the cells within @p reach cells
      /// of the cell of (x, y).
      template <typename Function>
      void
      for_each_near(const double x,
                    const double y,
                    const int    reach,
                    Function   &&f) const
      {
        const int cx = cell(x), cy = cell(y);
        for (int a = std::max(cx - reach, 0); a <= std::min(cx + reach, n - 1);
             ++a)
          for (int b = std::max(cy - reach, 0);
               b <= std::min(cy + reach, n - 1);
               ++b)
            for (const unsigned int j : cells[index(a, b)])
              f(j);
      }

    private:
      /// The cell index of coordinate @p x along one axis.
      int
      cell(const double x) const
      {
        return static_cast<int>(
          std::clamp(std::floor((x + half_width) / size), 0., n - 1.));
      }

      /// The position of cell (a, b) in #cells.
      std::size_t
      index(const int a, const int b) const
      {
        return static_cast<std::size_t>(a) * n + b;
      }

      /// Half the side of the covered square.
      const double half_width;
      /// Number of cells per side.
      const int n;
      /// Side of a cell.
      const double size;
      /// The particle indices in each cell, row by row.
      std::vector<std::vector<unsigned int>> cells;
    };



    /// Is (x, y) at least one diameter (up to round-off) from every particle
    /// but @p i?
    bool
    is_free(const std::vector<std::array<double, 2>> &centres,
            const CellGrid                           &grid,
            const double                              d,
            const unsigned int                        i,
            const double                              x,
            const double                              y)
    {
      bool free = true;
      grid.for_each_near(x, y, 1, [&](const unsigned int j) {
        const double dx = centres[j][0] - x, dy = centres[j][1] - y;
        if (j != i && dx * dx + dy * dy < d * d * (1. - 1e-13))
          free = false;
      });
      return free;
    }



    /// Move particle @p i to (x, y) (checked by the caller).
    void
    move(std::vector<std::array<double, 2>> &centres,
         CellGrid                           &grid,
         const unsigned int                  i,
         const double                        x,
         const double                        y)
    {
      grid.remove(i, centres[i][0], centres[i][1]);
      centres[i] = {{x, y}};
      grid.insert(i, x, y);
    }



    /**
     * Move particle @p i radially towards the axis by at most one diameter,
     * stopping just before it touches another particle. Returns the distance
     * moved; @p blocker is set to the particle touched (or to
     * centres.size() if none).
     */
    double
    fall(std::vector<std::array<double, 2>> &centres,
         CellGrid                           &grid,
         const double                        d,
         const unsigned int                  i,
         unsigned int                       &blocker)
    {
      blocker        = centres.size();
      const double x = centres[i][0], y = centres[i][1];
      const double r = std::hypot(x, y);
      if (r <= 0.)
        return 0.;
      const double ux = -x / r, uy = -y / r;
      const double s_max = std::min(r, d);
      // The first contact along the ray (x, y) + s (ux, uy).
      double s = s_max;
      grid.for_each_near(x, y, 2, [&](const unsigned int j) {
        if (j == i)
          return;
        const double wx = centres[j][0] - x, wy = centres[j][1] - y;
        const double b = wx * ux + wy * uy;
        if (b <= 0.)
          return;
        const double c    = wx * wx + wy * wy - d * d;
        const double disc = b * b - c;
        if (disc < 0.)
          return;
        const double contact = c > 0. ? c / (b + std::sqrt(disc)) : 0.;
        if (contact < s)
          {
            s       = contact;
            blocker = j;
          }
      });
      if (blocker < centres.size())
        s = std::max(s - 1e-12 * d, 0.);
      if (s <= 0.)
        return 0.;

      // Verify the new position against round-off before moving.
      const double nx = x + s * ux, ny = y + s * uy;
      if (!is_free(centres, grid, d, i, nx, ny))
        return 0.;
      move(centres, grid, i, nx, ny);
      return s;
    }



    /**
     * Roll particle @p i around the particle @p j it rests on, towards the
     * axis, in steps of at most 0.2 rad (halved down to 0.2/16 rad when a
     * step would overlap another particle), as long as this brings it closer
     * to the axis. Returns the distance moved.
     */
    double
    roll(std::vector<std::array<double, 2>> &centres,
         CellGrid                           &grid,
         const double                        d,
         const unsigned int                  i,
         const unsigned int                  j)
    {
      double moved = 0.;
      double angle = 0.2;
      for (unsigned int step = 0; step < 32 && angle > 0.2 / 17.; ++step)
        {
          const double x = centres[i][0], y = centres[i][1];
          const double r = std::hypot(x, y);
          // The two positions rotated about j, the one closer to the axis.
          const double ax = x - centres[j][0], ay = y - centres[j][1];
          const double c = std::cos(angle), s = std::sin(angle);
          double       best_x = x, best_y = y, best_r = r;
          for (const double sign : {1., -1.})
            {
              const double nx = centres[j][0] + c * ax - sign * s * ay;
              const double ny = centres[j][1] + sign * s * ax + c * ay;
              const double nr = std::hypot(nx, ny);
              if (nr < best_r - 1e-12 * d)
                {
                  best_x = nx;
                  best_y = ny;
                  best_r = nr;
                }
            }
          if (best_r >= r)
            break; // resting on j, straight outwards of it
          if (!is_free(centres, grid, d, i, best_x, best_y))
            {
              angle /= 2.;
              continue;
            }
          moved += std::hypot(best_x - x, best_y - y);
          move(centres, grid, i, best_x, best_y);
        }
      return moved;
    }



    /**
     * One relaxation sweep: in order of increasing distance from the axis,
     * move every particle radially towards the axis by at most one diameter
     * until it touches another one, then let it roll on that one towards the
     * axis. Returns the largest move.
     */
    double
    relaxation_sweep(std::vector<std::array<double, 2>> &centres,
                     CellGrid                           &grid,
                     const double                        d)
    {
      std::vector<unsigned int> order(centres.size());
      for (unsigned int i = 0; i < order.size(); ++i)
        order[i] = i;
      std::vector<double> distance(centres.size());
      for (unsigned int i = 0; i < centres.size(); ++i)
        distance[i] = std::hypot(centres[i][0], centres[i][1]);
      std::sort(order.begin(),
                order.end(),
                [&](const unsigned int a, const unsigned int b) {
                  return distance[a] < distance[b] ||
                         (distance[a] == distance[b] && a < b);
                });

      double largest_move = 0.;
      for (const unsigned int i : order)
        {
          unsigned int blocker = centres.size();
          double       moved   = fall(centres, grid, d, i, blocker);
          if (blocker < centres.size())
            moved += roll(centres, grid, d, i, blocker);
          largest_move = std::max(largest_move, moved);
        }
      return largest_move;
    }



    /// Relax until nothing moves by more than 1e-6 diameters.
    void
    relax(std::vector<std::array<double, 2>> &centres,
          CellGrid                           &grid,
          const double                        d,
          const double                        die_radius)
    {
      const unsigned int max_sweeps =
        20 + 4 * static_cast<unsigned int>(std::ceil(die_radius / d));
      for (unsigned int sweep = 0; sweep < max_sweeps; ++sweep)
        if (relaxation_sweep(centres, grid, d) < 1e-6 * d)
          break;
    }
  } // namespace



  double
  uniform_random(std::mt19937 &random)
  {
    const std::uint64_t a = random() >> 5;
    const std::uint64_t b = random() >> 6;
    return (a * 67108864. + b) / 9007199254740992.;
  }



  std::vector<Particle>
  hexagonal_layer(const double             die_diameter,
                  const double             particle_diameter,
                  const double             z_centre,
                  const std::string       &material,
                  const double             clearance,
                  const HexagonalPlacement placement)
  {
    require_positive("hexagonal_layer", "die diameter", die_diameter);
    require_positive("hexagonal_layer", "particle diameter", particle_diameter);
    if (!(clearance >= 0.) || !std::isfinite(clearance))
      throw std::runtime_error("hexagonal_layer: clearance " + fmt(clearance) +
                               " mm must be >= 0");

    const double d   = particle_diameter;
    const double rho = 0.5 * die_diameter - 0.5 * d - clearance +
                       1e-10 * die_diameter; // touching the wall is inside

    // The named placements, as offsets in lattice coordinates.
    const std::array<std::array<double, 2>, 3> named = {
      {{{0., 0.}}, {{1. / 3., 1. / 3.}}, {{0.5, 0.}}}};

    ClippedLattice lattice = lattice_at(d, rho, 0., 0.);
    switch (placement)
      {
        case HexagonalPlacement::particle_centred:
          break;
        case HexagonalPlacement::hole_centred:
          lattice = lattice_at(d, rho, named[1][0], named[1][1]);
          break;
        case HexagonalPlacement::edge_centred:
          lattice = lattice_at(d, rho, named[2][0], named[2][1]);
          break;
        case HexagonalPlacement::best:
          {
            std::vector<std::array<double, 2>> offsets(named.begin(),
                                                       named.end());
            const unsigned int                 n_grid = 24;
            for (unsigned int a = 0; a < n_grid; ++a)
              for (unsigned int b = 0; b < n_grid; ++b)
                offsets.push_back({{static_cast<double>(a) / n_grid,
                                    static_cast<double>(b) / n_grid}});
            unsigned long best_count = lattice.count();
            for (const auto &offset : offsets)
              {
                const ClippedLattice candidate =
                  lattice_at(d, rho, offset[0], offset[1]);
                const unsigned long count = candidate.count();
                if (count > best_count)
                  {
                    best_count = count;
                    lattice    = candidate;
                  }
              }
            break;
          }
      }

    std::vector<Particle> particles;
    for (const auto &p : lattice.points())
      {
        Particle particle;
        particle.centre   = Point<3>(p[0], p[1], z_centre);
        particle.diameter = d;
        particle.material = material;
        particles.push_back(particle);
      }
    return particles;
  }



  std::vector<Particle>
  random_layer(const double       die_diameter,
               const double       particle_diameter,
               const double       z_centre,
               const unsigned int n_particles,
               const unsigned int seed,
               const std::string &material,
               const unsigned int max_attempts)
  {
    require_positive("random_layer", "die diameter", die_diameter);
    require_positive("random_layer", "particle diameter", particle_diameter);

    const double      d          = particle_diameter;
    const double      die_radius = 0.5 * die_diameter;
    const double      rho        = die_radius - 0.5 * d; // centres' disc
    const std::string what = "cannot place " + std::to_string(n_particles) +
                             " particles of diameter " + fmt(d) +
                             " mm in a die of diameter " + fmt(die_diameter) +
                             " mm";
    if (n_particles == 0)
      return {};
    if (rho < 0.)
      throw std::runtime_error(what +
                               " (the particles are wider than the die): "
                               "lower the diameter");

    std::mt19937                       random(seed);
    std::vector<std::array<double, 2>> centres;
    CellGrid grid(die_radius, std::max(d, die_diameter / 2048.));

    // Relax after this many rejections in a row (and only once until the
    // next particle is placed).
    const unsigned int stall_limit     = 1000;
    unsigned int       rejected_in_row = 0;
    bool               relaxed         = false;
    unsigned int       attempts        = 0;
    while (centres.size() < n_particles && attempts < max_attempts)
      {
        // A uniform point in the disc of radius rho, by rejection from the
        // enclosing square (rejected points are not counted as attempts).
        double x = 0., y = 0.;
        do
          {
            x = rho * (2. * uniform_random(random) - 1.);
            y = rho * (2. * uniform_random(random) - 1.);
        } while (x * x + y * y > rho * rho);
        ++attempts;

        bool free = true;
        grid.for_each_near(x, y, 1, [&](const unsigned int j) {
          const double dx = centres[j][0] - x, dy = centres[j][1] - y;
          if (dx * dx + dy * dy < d * d)
            free = false;
        });
        if (free)
          {
            grid.insert(centres.size(), x, y);
            centres.push_back({{x, y}});
            rejected_in_row = 0;
            relaxed         = false;
          }
        else if (++rejected_in_row >= stall_limit && !relaxed)
          {
            relax(centres, grid, d, die_radius);
            relaxed         = true;
            rejected_in_row = 0;
          }
      }
    if (centres.size() < n_particles)
      throw std::runtime_error(what + " (placed " +
                               std::to_string(centres.size()) + " after " +
                               std::to_string(attempts) +
                               " attempts): lower the count or the diameter");

    relax(centres, grid, d, die_radius);

    std::vector<Particle> particles;
    for (const auto &c : centres)
      {
        Particle particle;
        particle.centre   = Point<3>(c[0], c[1], z_centre);
        particle.diameter = d;
        particle.material = material;
        particles.push_back(particle);
      }
    return particles;
  }



  double
  layer_relative_density(const std::vector<Particle> &particles,
                         const double                 die_diameter,
                         const double                 height)
  {
    require_positive("layer_relative_density", "die diameter", die_diameter);
    require_positive("layer_relative_density", "height", height);
    double volume = 0.;
    for (const Particle &p : particles)
      volume += particle_volume(p);
    const double R = 0.5 * die_diameter;
    return volume / (numbers::PI * R * R * height);
  }
} // namespace densify
