// Reading particles from CSV files and checking sizes, overlaps, container.
#include <densify/geometry/liggghts_dump.h>
#include <densify/geometry/number_field.h>
#include <densify/geometry/particle_shape.h>
#include <densify/geometry/particles.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace densify
{
  namespace
  {
    /// Remove leading and trailing white space (and a trailing '\r').
    std::string
    trim(const std::string &s)
    {
      const char *ws    = " \t\r\n\f\v";
      const auto  first = s.find_first_not_of(ws);
      if (first == std::string::npos)
        return "";
      const auto last = s.find_last_not_of(ws);
      return s.substr(first, last - first + 1);
    }



    /// Split @p line at every comma; fields are trimmed.
    std::vector<std::string>
    split_commas(const std::string &line)
    {
      std::vector<std::string> fields;
      std::string::size_type   begin = 0;
      while (true)
        {
          const auto end = line.find(',', begin);
          fields.push_back(trim(line.substr(begin, end - begin)));
          if (end == std::string::npos)
            break;
          begin = end + 1;
        }
      return fields;
    }



    /// A number with at most 6 significant digits, for messages.
    std::string
    fmt(const double x)
    {
      std::ostringstream s;
      s.precision(6);
      // Avoid printing "-0" for values that round to zero.
      s << (std::abs(x) < 5e-13 ? 0. : x);
      return s.str();
    }



    /**
     * Two numbers that are compared in a message ("a < b"): 6 significant
     * digits, or more if needed to tell them apart.
     */
    std::pair<std::string, std::string>
    fmt_distinct(const double a, const double b)
    {
      for (int digits = 6; digits < 17; ++digits)
        {
          std::ostringstream sa, sb;
          sa.precision(digits);
          sb.precision(digits);
          sa << a;
          sb << b;
          if (sa.str() != sb.str() || digits == 16)
            return {sa.str(), sb.str()};
        }
      return {fmt(a), fmt(b)};
    }



    /// The coordinates of a point, for messages: "(x, y, z)".
    std::string
    fmt(const Point<3> &p)
    {
      return "(" + fmt(p[0]) + ", " + fmt(p[1]) + ", " + fmt(p[2]) + ")";
    }



    /// Throw std::runtime_error with @p message.
    [[noreturn]] void
    fail(const std::string &message)
    {
      throw std::runtime_error(message);
    }



    /**
     * How far particles @p a and @p b overlap (mm; negative: the gap between
     * two spheres). A pair of which one is not a sphere is tested by
     * shape_overlap() if their bounding spheres overlap by more than
     * @p tolerance; @p inside and @p deepest tell where (see there).
     */
    double
    overlap_depth(const Particle &a,
                  const Particle &b,
                  const double    tolerance,
                  unsigned int   &inside,
                  Point<3>       &deepest)
    {
      const double bounding =
        0.5 * (a.diameter + b.diameter) - a.centre.distance(b.centre);
      if ((a.shape == ParticleShape::sphere &&
           b.shape == ParticleShape::sphere) ||
          !(bounding > tolerance))
        return bounding;
      return shape_overlap(a, b, inside, deepest);
    }



    /**
     * Find the lexicographically first pair (i < j) of particles that
     * overlap by more than @p tolerance (see overlap_depth()). The particles
     * are binned into a uniform grid of cell size = largest diameter (so
     * overlapping particles are in the same or in neighbouring cells), the bins
     * are sorted, and each particle is compared with the particles in the 27
     * surrounding bins: O(N log N) for any reasonable packing. Returns false if
     * none overlap.
     */
    bool
    find_first_overlap(const std::vector<Particle> &particles,
                       const double                 tolerance,
                       unsigned int                &first,
                       unsigned int                &second)
    {
      const unsigned int n = particles.size();
      if (n < 2)
        return false;

      double max_diameter = 0.;
      for (const Particle &p : particles)
        max_diameter = std::max(max_diameter, p.diameter);
      const double cell_size = max_diameter + std::max(tolerance, 0.);

      Point<3> lower = particles[0].centre;
      for (const Particle &p : particles)
        for (unsigned int d = 0; d < 3; ++d)
          lower[d] = std::min(lower[d], p.centre[d]);

      using Key   = std::array<std::int64_t, 3>;
      auto key_of = [&](const Point<3> &x) {
        Key key;
        for (unsigned int d = 0; d < 3; ++d)
          key[d] = static_cast<std::int64_t>(
            std::min(std::floor((x[d] - lower[d]) / cell_size),
                     1e15)); // no overflow
        return key;
      };

      std::vector<std::pair<Key, unsigned int>> bins(n);
      for (unsigned int i = 0; i < n; ++i)
        bins[i] = {key_of(particles[i].centre), i};
      std::sort(bins.begin(), bins.end());

      bool found = false;
      first      = n;
      second     = n;
      for (unsigned int i = 0; i < n && !found; ++i)
        {
          const Key    key    = key_of(particles[i].centre);
          unsigned int best_j = n;
          for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dz = -1; dz <= 1; ++dz)
                {
                  const Key neighbour = {
                    {key[0] + dx, key[1] + dy, key[2] + dz}};
                  const auto range =
                    std::equal_range(bins.begin(),
                                     bins.end(),
                                     std::make_pair(neighbour, 0u),
                                     [](const std::pair<Key, unsigned int> &a,
                                        const std::pair<Key, unsigned int> &b) {
                                       return a.first < b.first;
                                     });
                  for (auto it = range.first; it != range.second; ++it)
                    {
                      const unsigned int j = it->second;
                      if (j <= i || j >= best_j)
                        continue;
                      unsigned int inside = 0;
                      Point<3>     deepest;
                      if (overlap_depth(particles[i],
                                        particles[j],
                                        tolerance,
                                        inside,
                                        deepest) > tolerance)
                        best_j = j;
                    }
                }
          if (best_j < n)
            {
              first  = i;
              second = best_j;
              found  = true;
            }
        }
      return found;
    }
  } // namespace



  std::vector<Particle>
  read_particle_csv(const std::string &filename,
                    const std::string &default_material,
                    const unsigned int orientation_seed)
  {
    // a LIGGGHTS/LAMMPS text dump instead, told by its first line
    if (is_liggghts_dump(filename))
      return read_liggghts_dump(filename, default_material);

    errno = 0;
    std::ifstream in(filename);
    if (!in)
      {
        const int error = errno;
        fail("Particles/Particle file: cannot open '" + filename + "' (" +
             (error != 0 ? std::strerror(error) : "unknown error") + ")");
      }

    static const char *const names[4] = {"x", "y", "z", "diameter"};

    // random orientations, one particle after the other
    std::mt19937 random(orientation_seed);
    auto         uniform = [&random]() {
      return static_cast<double>(random()) / 4294967296.;
    };
    // a surface file read once for all its particles
    std::map<std::string, Particle> surfaces;

    std::vector<Particle> particles;
    std::string           line;
    unsigned int          line_number = 0;
    bool                  seen_data   = false;
    while (std::getline(in, line))
      {
        ++line_number;
        const std::string text = trim(line);
        if (text.empty() || text[0] == '#')
          continue;

        const std::vector<std::string> fields = split_commas(text);
        const std::string where = filename + ":" + std::to_string(line_number);

        // A header: the first non-comment line, starting with a non-number.
        double value = 0.;
        if (!seen_data && !parse_number(fields[0], value))
          {
            seen_data = true;
            continue;
          }
        seen_data = true;

        const std::string shape = fields.size() > 5 ? fields[5] : "";
        const bool        is_surface =
          shape.size() > 4 && (shape.substr(shape.size() - 4) == ".stl" ||
                               shape.substr(shape.size() - 4) == ".STL");
        if (fields.size() < 4 || fields.size() > 11 ||
            (fields.size() > 6 && shape == "sphere") ||
            (shape == "ellipsoid" && fields.size() != 8 &&
             fields.size() != 11) ||
            (is_surface && fields.size() != 6 && fields.size() != 9))
          fail(where +
               ": expected the comma-separated fields "
               "x,y,z,diameter[,material[,sphere | ,ellipsoid,diameter_y,"
               "diameter_z[,angle_x,angle_y,angle_z] | ,FILE.stl[,angle_x,"
               "angle_y,angle_z]]], got " +
               std::to_string(fields.size()));
        if (!shape.empty() && shape != "sphere" && shape != "ellipsoid" &&
            !is_surface)
          fail(where + ": field 6 (shape) '" + shape +
               "' is not 'sphere', 'ellipsoid' or a file name ending in "
               "'.stl'");

        Particle particle;
        double   numbers[4];
        for (unsigned int k = 0; k < 4; ++k)
          if (!(k == 3 && is_surface) && !parse_number(fields[k], numbers[k]))
            fail(where + ": field " + std::to_string(k + 1) + " (" + names[k] +
                 ") '" + fields[k] + "' is not a number");
        if (is_surface && !fields[3].empty())
          fail(where + ": field 4 (diameter) must be empty for a particle "
                       "from a surface file (its size comes from the file)");
        particle.centre   = Point<3>(numbers[0], numbers[1], numbers[2]);
        particle.diameter = is_surface ? 0. : numbers[3];
        particle.material = (fields.size() >= 5 && !fields[4].empty()) ?
                              fields[4] :
                              default_material;
        if (shape == "ellipsoid" || is_surface)
          {
            // the numbers after the shape: diameters, then angles
            const unsigned int  first = 6;
            std::vector<double> values;
            static const char  *value_names[5] = {
               "diameter_y", "diameter_z", "angle_x", "angle_y", "angle_z"};
            const unsigned int offset = is_surface ? 2 : 0;
            for (unsigned int k = first; k < fields.size(); ++k)
              {
                double value = 0;
                if (!parse_number(fields[k], value))
                  fail(where + ": field " + std::to_string(k + 1) + " (" +
                       value_names[k - first + offset] + ") '" + fields[k] +
                       "' is not a number");
                values.push_back(value);
              }
            const unsigned int n_diameters = is_surface ? 0 : 2;
            Tensor<2, 3>       rotation;
            if (values.size() == n_diameters + 3)
              rotation = rotation_from_angles({{values[n_diameters],
                                                values[n_diameters + 1],
                                                values[n_diameters + 2]}});
            else
              {
                std::array<double, 3> u;
                for (double &x : u)
                  x = uniform();
                rotation = uniform_rotation(u);
              }
            try
              {
                if (is_surface)
                  {
                    auto it = surfaces.find(shape);
                    if (it == surfaces.end())
                      {
                        Particle read;
                        make_surface_particle(read, shape, rotation);
                        it = surfaces.emplace(shape, read).first;
                      }
                    const Point<3>    centre   = particle.centre;
                    const std::string material = particle.material;
                    particle                   = it->second;
                    particle.centre            = centre;
                    particle.material          = material;
                    particle.rotation          = rotation;
                  }
                else
                  make_ellipsoid(particle,
                                 {{numbers[3], values[0], values[1]}},
                                 rotation);
              }
            catch (const std::exception &e)
              {
                fail(where + ": " + e.what());
              }
          }
        particles.push_back(particle);
      }
    if (in.bad())
      fail("Particles/Particle file: error while reading '" + filename + "'");

    return particles;
  }



  void
  check_particles(const std::vector<Particle> &particles,
                  const Container             &container,
                  const double                 tolerance)
  {
    const std::string where_to_move = "Particles/Centres or the particle file";

    // Sizes and positions must be usable numbers before anything else.
    for (unsigned int i = 0; i < particles.size(); ++i)
      {
        const Particle &p = particles[i];
        if (!(p.diameter > 0.) || !std::isfinite(p.diameter))
          fail("particle " + std::to_string(i) + ": diameter " +
               fmt(p.diameter) +
               " mm must be > 0 (Particles/Diameters or the particle file)");
        for (unsigned int d = 0; d < 3; ++d)
          if (!std::isfinite(p.centre[d]))
            fail("particle " + std::to_string(i) + ": centre " + fmt(p.centre) +
                 " is not finite (" + where_to_move + ")");
      }

    // The container: a sphere's radius, or the extent of another shape
    // (the largest distance of its points from the axis, above and below
    // its centre).
    for (unsigned int i = 0; i < particles.size(); ++i)
      {
        const Particle   &p      = particles[i];
        const bool        sphere = p.shape == ParticleShape::sphere;
        const std::string size   = sphere ? " mm + radius " : " mm + extent ";
        const std::string name   = "particle " + std::to_string(i);
        if (container.has_die)
          {
            const double axis_distance = std::hypot(p.centre[0], p.centre[1]);
            const double outer         = axis_distance_extent(p);
            const double r             = outer - axis_distance;
            const double excess        = outer - container.die_radius;
            if (excess > tolerance)
              fail(name + " crosses the die wall by " + fmt(excess) +
                   " mm (distance from axis " + fmt(axis_distance) + size +
                   fmt(r) + " mm > die radius " + fmt(container.die_radius) +
                   " mm): move it inwards in " + where_to_move +
                   " or set Tools/Die wall/Diameter to at least " +
                   fmt(2. * outer) + " mm");
          }
        if (container.has_lower)
          {
            const double r      = support(p, Point<3>(0., 0., -1.));
            const double excess = container.lower_z - (p.centre[2] - r);
            if (excess > tolerance)
              fail(name + " is below the lower punch by " + fmt(excess) +
                   " mm (centre z " + fmt(p.centre[2]) +
                   (sphere ? " mm - radius " : " mm - extent ") + fmt(r) +
                   " mm < lower punch face " + fmt(container.lower_z) +
                   " mm): move it up in " + where_to_move +
                   " or set Tools/Lower punch/Position to at most " +
                   fmt(p.centre[2] - r) + " mm");
          }
        if (container.has_upper)
          {
            const double r      = support(p, Point<3>(0., 0., 1.));
            const double excess = p.centre[2] + r - container.upper_z;
            if (excess > tolerance)
              fail(name + " is above the upper punch by " + fmt(excess) +
                   " mm (centre z " + fmt(p.centre[2]) + size + fmt(r) +
                   " mm > upper punch face " + fmt(container.upper_z) +
                   " mm): move it down in " + where_to_move +
                   " or set Tools/Upper punch/Initial position to at least " +
                   fmt(p.centre[2] + r) + " mm");
          }
      }

    // Pairwise overlaps.
    unsigned int i = 0, j = 0;
    if (find_first_overlap(particles, tolerance, i, j))
      {
        if (particles[i].shape == ParticleShape::sphere &&
            particles[j].shape == ParticleShape::sphere)
          {
            const double distance =
              particles[i].centre.distance(particles[j].centre);
            const double radii =
              0.5 * (particles[i].diameter + particles[j].diameter);
            const auto [d, r] = fmt_distinct(distance, radii);
            fail("particles " + std::to_string(i) + " and " +
                 std::to_string(j) + " overlap by " + fmt(radii - distance) +
                 " mm (centre distance " + d + " mm < sum of radii " + r +
                 " mm): move them apart in " + where_to_move);
          }
        unsigned int inside = 0;
        Point<3>     deepest;
        const double depth =
          shape_overlap(particles[i], particles[j], inside, deepest);
        const unsigned int a = inside == 0 ? i : j, b = inside == 0 ? j : i;
        fail("particles " + std::to_string(i) + " and " + std::to_string(j) +
             " overlap by at least " + fmt(depth) + " mm (the point " +
             fmt(deepest) + " of particle " + std::to_string(a) +
             "'s surface lies " + fmt(depth) + " mm inside particle " +
             std::to_string(b) + "): move them apart in " + where_to_move);
      }
  }
} // namespace densify
