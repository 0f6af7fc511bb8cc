// The shapes of particles that are not spheres: extent, volume, inside test
// and overlaps.
#include <deal.II/base/numbers.h>

#include <densify/contact/closest_point.h>
#include <densify/geometry/particle_shape.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// Throw std::runtime_error with "surface file 'NAME': @p what".
    [[noreturn]] void
    fail_file(const std::string &filename, const std::string &what)
    {
      throw std::runtime_error("surface file '" + filename + "': " + what);
    }



    /// Add triangle (a, b, c) to @p surface, merging equal vertices.
    void
    add_triangle(const std::array<Point<3>, 3>                 &corners,
                 std::map<std::array<double, 3>, unsigned int> &index,
                 SurfaceMesh                                   &surface)
    {
      std::array<unsigned int, 3> triangle;
      for (unsigned int k = 0; k < 3; ++k)
        {
          const std::array<double, 3> key = {
            {corners[k][0], corners[k][1], corners[k][2]}};
          const auto it = index.find(key);
          if (it != index.end())
            triangle[k] = it->second;
          else
            {
              triangle[k] = surface.vertices.size();
              index.emplace(key, triangle[k]);
              surface.vertices.push_back(corners[k]);
            }
        }
      // degenerate triangles (two equal corners) carry nothing
      if (triangle[0] != triangle[1] && triangle[1] != triangle[2] &&
          triangle[0] != triangle[2])
        surface.triangles.push_back(triangle);
    }



    /// The unit sphere as a subdivided icosahedron (level 4: 2562 vertices,
    /// 5120 triangles, outward).
    const SurfaceMesh &
    unit_icosphere()
    {
      static const SurfaceMesh sphere = []() {
        SurfaceMesh  s;
        const double t        = (1. + std::sqrt(5.)) / 2.;
        const double v[12][3] = {{-1, t, 0},
                                 {1, t, 0},
                                 {-1, -t, 0},
                                 {1, -t, 0},
                                 {0, -1, t},
                                 {0, 1, t},
                                 {0, -1, -t},
                                 {0, 1, -t},
                                 {t, 0, -1},
                                 {t, 0, 1},
                                 {-t, 0, -1},
                                 {-t, 0, 1}};
        for (const auto &p : v)
          {
            const Point<3> x(p[0], p[1], p[2]);
            s.vertices.push_back(x / x.norm());
          }
        s.triangles = {{{0, 11, 5}},  {{0, 5, 1}},  {{0, 1, 7}},  {{0, 7, 10}},
                       {{0, 10, 11}}, {{1, 5, 9}},  {{5, 11, 4}}, {{11, 10, 2}},
                       {{10, 7, 6}},  {{7, 1, 8}},  {{3, 9, 4}},  {{3, 4, 2}},
                       {{3, 2, 6}},   {{3, 6, 8}},  {{3, 8, 9}},  {{4, 9, 5}},
                       {{2, 4, 11}},  {{6, 2, 10}}, {{8, 6, 7}},  {{9, 8, 1}}};
        for (unsigned int level = 0; level < 4; ++level)
          {
            std::map<std::pair<unsigned int, unsigned int>, unsigned int> mid;
            auto midpoint = [&](unsigned int a, unsigned int b) {
              const auto key = std::make_pair(std::min(a, b), std::max(a, b));
              const auto it  = mid.find(key);
              if (it != mid.end())
                return it->second;
              const Point<3> m = s.vertices[a] + s.vertices[b];
              s.vertices.push_back(m / m.norm());
              mid.emplace(key, s.vertices.size() - 1);
              return static_cast<unsigned int>(s.vertices.size() - 1);
            };
            std::vector<std::array<unsigned int, 3>> finer;
            for (const auto &tri : s.triangles)
              {
                const unsigned int a = midpoint(tri[0], tri[1]),
                                   b = midpoint(tri[1], tri[2]),
                                   c = midpoint(tri[2], tri[0]);
                finer.push_back({{tri[0], a, c}});
                finer.push_back({{tri[1], b, a}});
                finer.push_back({{tri[2], c, b}});
                finer.push_back({{a, b, c}});
              }
            s.triangles = finer;
          }
        return s;
      }();
      return sphere;
    }



    /// The particle's surface as a closed triangulation in global
    /// coordinates (spheres and ellipsoids: the icosphere mapped onto them).
    SurfaceMesh
    global_surface(const Particle &p)
    {
      SurfaceMesh s;
      if (p.shape == ParticleShape::surface)
        {
          s.triangles = p.surface->triangles;
          for (const Point<3> &v : p.surface->vertices)
            s.vertices.push_back(p.centre + p.rotation * v);
          return s;
        }
      const SurfaceMesh &unit = unit_icosphere();
      s.triangles             = unit.triangles;
      for (const Point<3> &v : unit.vertices)
        {
          Tensor<1, 3> body;
          for (unsigned int d = 0; d < 3; ++d)
            body[d] =
              v[d] * (p.shape == ParticleShape::ellipsoid ? p.semi_axes[d] :
                                                            p.diameter / 2);
          s.vertices.push_back(p.centre + p.rotation * body);
        }
      return s;
    }



    /// The distance from @p x to the triangle (a, b, c).
    double
    distance_to_triangle(const Point<3> &x,
                         const Point<3> &a,
                         const Point<3> &b,
                         const Point<3> &c)
    {
      const std::array<double, 3> l = closest_on_triangle(x, a, b, c);
      return x.distance(a + l[1] * (b - a) + l[2] * (c - a));
    }



    /// The distance from @p x to the closest triangle of @p s.
    double
    distance_to_surface(const Point<3> &x, const SurfaceMesh &s)
    {
      double d = std::numeric_limits<double>::max();
      for (const auto &t : s.triangles)
        d = std::min(d,
                     distance_to_triangle(x,
                                          s.vertices[t[0]],
                                          s.vertices[t[1]],
                                          s.vertices[t[2]]));
      return d;
    }



    /// The winding number of the closed surface @p s about @p x (body
    /// frame): +-1 inside, 0 outside (van Oosterom and Strackee's solid
    /// angle of each triangle).
    double
    winding_number(const SurfaceMesh &s, const Tensor<1, 3> &x)
    {
      double total = 0;
      for (const auto &t : s.triangles)
        {
          const Tensor<1, 3> a = s.vertices[t[0]] - x, b = s.vertices[t[1]] - x,
                             c = s.vertices[t[2]] - x;
          const double la = a.norm(), lb = b.norm(), lc = c.norm();
          const double numerator = a * cross_product_3d(b, c);
          const double denominator =
            la * lb * lc + (a * b) * lc + (a * c) * lb + (b * c) * la;
          total += 2. * std::atan2(numerator, denominator);
        }
      return total / (4. * numbers::PI);
    }



    /// The depth of @p x inside @p p (its distance to the surface @p s
    /// of @p p; the sphere's exactly).
    double
    depth_inside(const Particle &p, const SurfaceMesh &s, const Point<3> &x)
    {
      if (p.shape == ParticleShape::sphere)
        return p.diameter / 2 - x.distance(p.centre);
      return distance_to_surface(x, s);
    }
  } // namespace



  SurfaceMesh
  read_stl(const std::string &filename)
  {
    std::ifstream in(filename, std::ios::binary);
    if (!in)
      fail_file(filename,
                std::string("cannot open it (") + std::strerror(errno) + ")");
    const std::string bytes((std::istreambuf_iterator<char>(in)),
                            std::istreambuf_iterator<char>());

    SurfaceMesh                                   surface;
    std::map<std::array<double, 3>, unsigned int> index;
    std::uint32_t                                 n_binary = 0;
    if (bytes.size() >= 84)
      std::memcpy(&n_binary, bytes.data() + 80, 4);
    if (bytes.size() >= 84 && bytes.size() == 84 + 50 * std::size_t(n_binary))
      {
        for (std::uint32_t t = 0; t < n_binary; ++t)
          {
            std::array<Point<3>, 3> corners;
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int d = 0; d < 3; ++d)
                {
                  float value;
                  std::memcpy(&value,
                              bytes.data() + 84 + 50 * t + 12 + 12 * k + 4 * d,
                              4);
                  corners[k][d] = value;
                }
            add_triangle(corners, index, surface);
          }
      }
    else
      {
        std::istringstream      text(bytes);
        std::string             word;
        std::array<Point<3>, 3> corners;
        unsigned int            k = 0;
        while (text >> word)
          if (word == "vertex")
            {
              for (unsigned int d = 0; d < 3; ++d)
                if (!(text >> corners[k][d]) || !std::isfinite(corners[k][d]))
                  fail_file(filename,
                            "a vertex has no three numbers (neither ASCII nor "
                            "binary STL)");
              if (++k == 3)
                {
                  add_triangle(corners, index, surface);
                  k = 0;
                }
            }
        if (k != 0)
          fail_file(filename, "a facet has fewer than three vertices");
      }
    if (surface.triangles.empty())
      fail_file(filename, "no triangles (neither ASCII nor binary STL)");

    // closed and consistently oriented: every directed edge once, with its
    // reverse
    std::map<std::pair<unsigned int, unsigned int>, unsigned int> edges;
    for (const auto &t : surface.triangles)
      for (unsigned int k = 0; k < 3; ++k)
        ++edges[{t[k], t[(k + 1) % 3]}];
    for (const auto &[edge, count] : edges)
      {
        const auto reverse = edges.find({edge.second, edge.first});
        if (count != 1 || reverse == edges.end() || reverse->second != 1)
          {
            const Point<3>    &a = surface.vertices[edge.first];
            std::ostringstream where;
            where << "not a closed, consistently oriented surface (the edge "
                     "at ("
                  << a[0] << ", " << a[1] << ", " << a[2]
                  << ") does not join exactly two triangles the same way)";
            fail_file(filename, where.str());
          }
      }
    const double volume = enclosed_volume(surface);
    if (!(std::abs(volume) > 0.) || !std::isfinite(volume))
      fail_file(filename, "the surface encloses no volume");
    if (volume < 0)
      for (auto &t : surface.triangles)
        std::swap(t[1], t[2]);
    return surface;
  }



  double
  enclosed_volume(const SurfaceMesh &surface)
  {
    double volume6 = 0;
    for (const auto &t : surface.triangles)
      volume6 += Tensor<1, 3>(surface.vertices[t[0]]) *
                 cross_product_3d(Tensor<1, 3>(surface.vertices[t[1]]),
                                  Tensor<1, 3>(surface.vertices[t[2]]));
    return volume6 / 6;
  }



  Point<3>
  enclosed_centroid(const SurfaceMesh &surface)
  {
    // tetrahedra (origin, a, b, c): centroid (a + b + c) / 4
    double       volume6 = 0;
    Tensor<1, 3> moment;
    for (const auto &t : surface.triangles)
      {
        const Tensor<1, 3> a = surface.vertices[t[0]],
                           b = surface.vertices[t[1]],
                           c = surface.vertices[t[2]];
        const double v       = a * cross_product_3d(b, c);
        volume6 += v;
        moment += v * (a + b + c) / 4;
      }
    return Point<3>(moment / volume6);
  }



  Tensor<2, 3>
  rotation_from_angles(const std::array<double, 3> &angles)
  {
    Tensor<2, 3> r = unit_symmetric_tensor<3>();
    for (unsigned int axis = 0; axis < 3; ++axis)
      {
        const double       a = angles[axis] * numbers::PI / 180;
        Tensor<2, 3>       q;
        const unsigned int i = (axis + 1) % 3, j = (axis + 2) % 3;
        q[axis][axis] = 1;
        q[i][i]       = std::cos(a);
        q[j][j]       = std::cos(a);
        q[i][j]       = -std::sin(a);
        q[j][i]       = std::sin(a);
        r             = q * r;
      }
    return r;
  }



  Tensor<2, 3>
  uniform_rotation(const std::array<double, 3> &u)
  {
    // Shoemake: a unit quaternion uniform on the 3-sphere
    const double s1 = std::sqrt(1 - u[0]), s2 = std::sqrt(u[0]);
    const double w = s1 * std::sin(2 * numbers::PI * u[1]),
                 x = s1 * std::cos(2 * numbers::PI * u[1]),
                 y = s2 * std::sin(2 * numbers::PI * u[2]),
                 z = s2 * std::cos(2 * numbers::PI * u[2]);
    Tensor<2, 3> r;
    r[0][0] = 1 - 2 * (y * y + z * z);
    r[0][1] = 2 * (x * y - z * w);
    r[0][2] = 2 * (x * z + y * w);
    r[1][0] = 2 * (x * y + z * w);
    r[1][1] = 1 - 2 * (x * x + z * z);
    r[1][2] = 2 * (y * z - x * w);
    r[2][0] = 2 * (x * z - y * w);
    r[2][1] = 2 * (y * z + x * w);
    r[2][2] = 1 - 2 * (x * x + y * y);
    return r;
  }



  void
  make_ellipsoid(Particle                    &particle,
                 const std::array<double, 3> &diameters,
                 const Tensor<2, 3>          &rotation)
  {
    for (unsigned int d = 0; d < 3; ++d)
      if (!(diameters[d] > 0) || !std::isfinite(diameters[d]))
        {
          std::ostringstream s;
          s << "ellipsoid diameter " << diameters[d] << " mm must be > 0";
          throw std::runtime_error(s.str());
        }
    particle.shape = ParticleShape::ellipsoid;
    for (unsigned int d = 0; d < 3; ++d)
      particle.semi_axes[d] = diameters[d] / 2;
    particle.rotation = rotation;
    particle.diameter = *std::max_element(diameters.begin(), diameters.end());
  }



  void
  make_surface_particle(Particle           &particle,
                        const std::string  &filename,
                        const Tensor<2, 3> &rotation)
  {
    SurfaceMesh    surface  = read_stl(filename);
    const Point<3> centroid = enclosed_centroid(surface);
    double         radius   = 0;
    for (Point<3> &v : surface.vertices)
      {
        v      = Point<3>(v - centroid);
        radius = std::max(radius, v.norm());
      }
    particle.shape        = ParticleShape::surface;
    particle.rotation     = rotation;
    particle.surface_file = filename;
    particle.surface      = std::make_shared<const SurfaceMesh>(surface);
    particle.diameter     = 2 * radius;
  }



  double
  support(const Particle &p, const Tensor<1, 3> &n)
  {
    switch (p.shape)
      {
        case ParticleShape::ellipsoid:
          {
            const Tensor<1, 3> body = transpose(p.rotation) * n;
            double             h2   = 0;
            for (unsigned int d = 0; d < 3; ++d)
              h2 += std::pow(p.semi_axes[d] * body[d], 2);
            return std::sqrt(h2);
          }
        case ParticleShape::surface:
          {
            double h = -std::numeric_limits<double>::max();
            for (const Point<3> &v : p.surface->vertices)
              h = std::max(h, n * (p.rotation * Tensor<1, 3>(v)));
            return h;
          }
        default:
          return p.diameter / 2;
      }
  }



  Tensor<1, 3>
  body_support_point(const Particle &p, const Tensor<1, 3> &n)
  {
    const Tensor<1, 3> body = transpose(p.rotation) * n;
    switch (p.shape)
      {
        case ParticleShape::ellipsoid:
          {
            Tensor<1, 3> x;
            for (unsigned int d = 0; d < 3; ++d)
              x[d] = std::pow(p.semi_axes[d], 2) * body[d];
            return x / support(p, n);
          }
        case ParticleShape::surface:
          {
            Tensor<1, 3> best = p.surface->vertices[0];
            for (const Point<3> &v : p.surface->vertices)
              if (body * v > body * best)
                best = v;
            return best;
          }
        default:
          return p.diameter / 2 * n / n.norm();
      }
  }



  double
  axis_distance_extent(const Particle &p)
  {
    switch (p.shape)
      {
        case ParticleShape::ellipsoid:
          {
            // the largest c.n + h(n) over horizontal unit vectors n
            const unsigned int k      = 4096;
            double             extent = 0;
            for (unsigned int i = 0; i < k; ++i)
              {
                const double   phi = 2 * numbers::PI * i / k;
                const Point<3> n(std::cos(phi), std::sin(phi), 0.);
                extent =
                  std::max(extent, Tensor<1, 3>(p.centre) * n + support(p, n));
              }
            return extent;
          }
        case ParticleShape::surface:
          {
            double extent = 0;
            for (const Point<3> &v : p.surface->vertices)
              {
                const Point<3> x = p.centre + p.rotation * Tensor<1, 3>(v);
                extent           = std::max(extent, std::hypot(x[0], x[1]));
              }
            return extent;
          }
        default:
          return std::hypot(p.centre[0], p.centre[1]) + p.diameter / 2;
      }
  }



  double
  particle_volume(const Particle &p)
  {
    switch (p.shape)
      {
        case ParticleShape::ellipsoid:
          return 4. / 3. * numbers::PI * p.semi_axes[0] * p.semi_axes[1] *
                 p.semi_axes[2];
        case ParticleShape::surface:
          return enclosed_volume(*p.surface);
        default:
          return numbers::PI / 6. * std::pow(p.diameter, 3);
      }
  }



  double
  smallest_width(const Particle &p)
  {
    switch (p.shape)
      {
        case ParticleShape::ellipsoid:
          return 2 * std::min({p.semi_axes[0], p.semi_axes[1], p.semi_axes[2]});
        case ParticleShape::surface:
          {
            double width = std::numeric_limits<double>::max();
            for (unsigned int d = 0; d < 3; ++d)
              {
                double low = 0, high = 0;
                for (const Point<3> &v : p.surface->vertices)
                  {
                    low  = std::min(low, v[d]);
                    high = std::max(high, v[d]);
                  }
                width = std::min(width, high - low);
              }
            return width;
          }
        default:
          return p.diameter;
      }
  }



  bool
  contains(const Particle &p, const Point<3> &x)
  {
    const Tensor<1, 3> body = transpose(p.rotation) * (x - p.centre);
    switch (p.shape)
      {
        case ParticleShape::ellipsoid:
          {
            double q = 0;
            for (unsigned int d = 0; d < 3; ++d)
              q += std::pow(body[d] / p.semi_axes[d], 2);
            return q < 1;
          }
        case ParticleShape::surface:
          return std::abs(winding_number(*p.surface, body)) > 0.5;
        default:
          return x.distance(p.centre) < p.diameter / 2;
      }
  }



  double
  shape_overlap(const Particle &a,
                const Particle &b,
                unsigned int   &inside,
                Point<3>       &deepest)
  {
    const std::array<const Particle *, 2> pair     = {{&a, &b}};
    const std::array<SurfaceMesh, 2>      surfaces = {
           {global_surface(a), global_surface(b)}};
    double depth = 0;
    inside       = 0;
    deepest      = a.centre;
    for (unsigned int k = 0; k < 2; ++k)
      {
        const Particle &other = *pair[1 - k];
        const double    reach = other.diameter / 2;
        for (const Point<3> &x : surfaces[k].vertices)
          if (x.distance(other.centre) < reach && contains(other, x))
            {
              const double d = depth_inside(other, surfaces[1 - k], x);
              if (d > depth)
                {
                  depth   = d;
                  inside  = k;
                  deepest = x;
                }
            }
      }
    return depth;
  }
} // namespace densify
