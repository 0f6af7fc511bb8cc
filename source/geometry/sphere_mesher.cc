// Tetrahedral meshes of single particles (spheres, ellipsoids, closed
// surfaces) through the gmsh C++ API.
#include <deal.II/base/numbers.h>

#include <densify/geometry/particle_shape.h>
#include <densify/geometry/sphere_mesher.h>

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace densify
{
  namespace
  {
    /**
     * Make sure the gmsh API is initialised, silently. gmsh is initialised
     * once per process and never finalised here; if somebody else finalised
     * it in the meantime (e.g. GridIn::read_msh does), it is initialised
     * again. Before the very first initialisation, gmsh's option calls do not
     * throw, after a finalize they throw "Gmsh has not been initialized":
     * hence the static flag plus the probe.
     */
    void
    ensure_gmsh_initialized()
    {
      static bool initialized = false;
      if (initialized)
        {
          try
            {
              double terminal = 0.;
              gmsh::option::getNumber("General.Terminal", terminal);
            }
          catch (...)
            {
              initialized = false;
            }
        }
      if (!initialized)
        {
          // No configuration files: the result must not depend on the user's
          // ~/.gmshrc.
          gmsh::initialize(0, nullptr, false);
          initialized = true;
        }
      gmsh::option::setNumber("General.Terminal", 0);
      gmsh::option::setNumber("General.Verbosity", 0);
    }



    /// A number in full precision for a gmsh MathEval expression.
    std::string
    number(const double x)
    {
      std::ostringstream s;
      s << std::setprecision(17) << x;
      return "(" + s.str() + ")";
    }



    /**
     * The MathEval expression of the size field
     * h = Min(element_size, refined + growth * Min_k |x - p_k|) for the
     * refinement points @p points.
     */
    std::string
    size_field_expression(const SphereMeshSpec        &spec,
                          const std::vector<Point<3>> &points)
    {
      std::string distance;
      for (const Point<3> &p : points)
        {
          const std::string d = "Sqrt((x-" + number(p[0]) + ")^2+(y-" +
                                number(p[1]) + ")^2+(z-" + number(p[2]) +
                                ")^2)";
          distance = distance.empty() ? d : "Min(" + distance + "," + d + ")";
        }
      return "Min(" + number(spec.element_size) + "," +
             number(spec.refined_element_size) + "+" + number(spec.growth) +
             "*" + distance + ")";
    }



    /// Throw std::runtime_error unless @p spec describes a meshable sphere.
    void
    check_spec(const SphereMeshSpec &spec)
    {
      auto fail = [](const std::string &what, const double value) {
        std::ostringstream s;
        s << "sphere mesher: " << what << " " << value << " must be > 0";
        throw std::runtime_error(s.str());
      };
      if (!(spec.radius > 0.) || !std::isfinite(spec.radius))
        fail("radius (mm)", spec.radius);
      if (!(spec.element_size > 0.) || !std::isfinite(spec.element_size))
        fail("element size (mm)", spec.element_size);
      if (!spec.refinement_directions.empty())
        {
          if (!(spec.refined_element_size > 0.) ||
              !std::isfinite(spec.refined_element_size))
            fail("refined element size (mm)", spec.refined_element_size);
          if (!(spec.growth >= 0.) || !std::isfinite(spec.growth))
            throw std::runtime_error(
              "sphere mesher: growth must be >= 0 and finite");
          for (const Tensor<1, 3> &direction : spec.refinement_directions)
            if (!(direction.norm() > 0.) || !std::isfinite(direction.norm()))
              throw std::runtime_error(
                "sphere mesher: a refinement direction is zero or not finite");
        }
    }



    /// Signed six-fold volume of the tetrahedron (a, b, c, d).
    double
    signed_volume6(const Point<3> &a,
                   const Point<3> &b,
                   const Point<3> &c,
                   const Point<3> &d)
    {
      const Tensor<1, 3> e1 = b - a, e2 = c - a, e3 = d - a;
      return scalar_product(e1, cross_product_3d(e2, e3));
    }



    /**
     * Build the geometry by @p build in the current gmsh model, mesh it with
     * the size field of @p spec refined towards @p points and copy the
     * linear tets into @p mesh.
     */
    void
    mesh_current_model(const SphereMeshSpec        &spec,
                       const std::vector<Point<3>> &points,
                       const std::function<void()> &build,
                       TetMesh                     &mesh)
    {
      build();

      // Options are global in gmsh: set every one that matters on each call.
      gmsh::option::setNumber("General.NumThreads", 1);
      gmsh::option::setNumber("Mesh.RandomSeed", 1);
      gmsh::option::setNumber("Mesh.Algorithm3D", 1); // Delaunay
      gmsh::option::setNumber("Mesh.ElementOrder", 1);
      gmsh::option::setNumber("Mesh.MeshSizeFactor", 1.);
      gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
      if (points.empty())
        {
          gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
          gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 1);
          gmsh::option::setNumber("Mesh.MeshSizeMin", spec.element_size);
          gmsh::option::setNumber("Mesh.MeshSizeMax", spec.element_size);
        }
      else
        {
          const int field = gmsh::model::mesh::field::add("MathEval");
          gmsh::model::mesh::field::setString(
            field, "F", size_field_expression(spec, points));
          gmsh::model::mesh::field::setAsBackgroundMesh(field);
          gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
          gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
          gmsh::option::setNumber("Mesh.MeshSizeMin", 0.);
          gmsh::option::setNumber("Mesh.MeshSizeMax", spec.element_size);
        }

      gmsh::model::mesh::generate(3);

      // All 4-node tetrahedra (gmsh element type 4) of all volumes.
      std::vector<std::size_t> element_tags, element_nodes;
      gmsh::model::mesh::getElementsByType(4, element_tags, element_nodes);
      if (element_tags.empty())
        throw std::string("no tetrahedra were generated");

      std::vector<std::size_t> node_tags;
      std::vector<double>      coordinates, parametric;
      gmsh::model::mesh::getNodes(
        node_tags, coordinates, parametric, -1, -1, false, false);

      // Keep only the nodes used by tets, numbered 0, 1, ... in the order of
      // their gmsh tags (so the geometric vertices, e.g. the poles, come
      // first).
      std::unordered_map<std::size_t, std::size_t> position_of_tag;
      for (std::size_t k = 0; k < node_tags.size(); ++k)
        position_of_tag[node_tags[k]] = k;
      std::vector<std::size_t> used_tags(element_nodes);
      std::sort(used_tags.begin(), used_tags.end());
      used_tags.erase(std::unique(used_tags.begin(), used_tags.end()),
                      used_tags.end());

      std::unordered_map<std::size_t, unsigned int> index_of_tag;
      mesh.vertices.clear();
      mesh.vertices.reserve(used_tags.size());
      for (const std::size_t tag : used_tags)
        {
          const auto it = position_of_tag.find(tag);
          if (it == position_of_tag.end())
            throw std::string("a tetrahedron refers to an unknown node");
          const std::size_t k = it->second;
          index_of_tag[tag]   = mesh.vertices.size();
          mesh.vertices.emplace_back(coordinates[3 * k],
                                     coordinates[3 * k + 1],
                                     coordinates[3 * k + 2]);
        }

      mesh.cells.resize(element_tags.size());
      for (std::size_t e = 0; e < element_tags.size(); ++e)
        {
          std::array<unsigned int, 4> &cell = mesh.cells[e];
          for (unsigned int v = 0; v < 4; ++v)
            cell[v] = index_of_tag[element_nodes[4 * e + v]];
          // deal.II's reference tet is (0,0,0), (1,0,0), (0,1,0), (0,0,1):
          // the Jacobian is positive iff det[x1-x0, x2-x0, x3-x0] > 0.
          const double volume6 = signed_volume6(mesh.vertices[cell[0]],
                                                mesh.vertices[cell[1]],
                                                mesh.vertices[cell[2]],
                                                mesh.vertices[cell[3]]);
          if (volume6 < 0.)
            std::swap(cell[2], cell[3]);
          else if (!(volume6 > 0.))
            throw std::string("gmsh produced a tetrahedron of zero volume");
        }
    }



    /**
     * Mesh in a gmsh model of its own (see mesh_sphere()); @p what names the
     * body in an error message.
     */
    TetMesh
    mesh_in_own_model(const SphereMeshSpec        &spec,
                      const std::vector<Point<3>> &points,
                      const std::function<void()> &build,
                      const std::string           &what)
    {
      static unsigned int n_models = 0;
      const std::string   model =
        "densify-particle-" + std::to_string(n_models++);

      TetMesh     mesh;
      bool        model_added = false;
      std::string previous_model;
      try
        {
          ensure_gmsh_initialized();
          gmsh::model::getCurrent(previous_model);
          gmsh::model::add(model);
          model_added = true;
          mesh_current_model(spec, points, build, mesh);
          gmsh::model::remove();
          model_added = false;
        }
      catch (...)
        {
          std::string message;
          try
            {
              throw;
            }
          catch (const std::string &s)
            {
              message = s;
            }
          catch (const std::exception &e)
            {
              message = e.what();
            }
          catch (...)
            {
              message = "unknown error";
            }
          // Leave gmsh usable: drop the half-built model.
          if (model_added)
            try
              {
                gmsh::model::setCurrent(model);
                gmsh::model::remove();
                gmsh::model::setCurrent(previous_model);
              }
            catch (...)
              {}
          std::replace(message.begin(), message.end(), '\n', ' ');
          std::ostringstream s;
          s << "gmsh failed to mesh " << what << " with element size "
            << spec.element_size << " mm: " << message;
          throw std::runtime_error(s.str());
        }

      // Leave the model that was current before current again.
      try
        {
          gmsh::model::setCurrent(previous_model);
        }
      catch (...)
        {}
      return mesh;
    }
  } // namespace



  TetMesh
  mesh_sphere(const SphereMeshSpec &spec)
  {
    check_spec(spec);
    std::vector<Point<3>> points;
    for (const Tensor<1, 3> &direction : spec.refinement_directions)
      points.emplace_back(spec.radius * direction / direction.norm());
    std::ostringstream what;
    what << "a sphere of radius " << spec.radius << " mm";
    try
      {
        return mesh_in_own_model(
          spec,
          points,
          [&spec]() {
            gmsh::model::occ::addSphere(0., 0., 0., spec.radius);
            gmsh::model::occ::synchronize();
          },
          what.str());
      }
    catch (const std::runtime_error &e)
      {
        throw std::runtime_error(std::string("sphere mesher: ") + e.what());
      }
  }



  TetMesh
  mesh_particle(const Particle &particle, const SphereMeshSpec &spec)
  {
    if (particle.shape == ParticleShape::sphere)
      {
        SphereMeshSpec sphere = spec;
        sphere.radius         = particle.diameter / 2;
        return mesh_sphere(sphere);
      }
    SphereMeshSpec checked = spec;
    checked.radius         = particle.diameter / 2;
    check_spec(checked);

    // the refinement points: where the particle reaches farthest along each
    // direction (global), in the body frame
    std::vector<Point<3>> points;
    for (const Tensor<1, 3> &direction : spec.refinement_directions)
      points.emplace_back(
        body_support_point(particle, direction / direction.norm()));

    std::function<void()> build;
    std::string           what;
    if (particle.shape == ParticleShape::ellipsoid)
      {
        const Tensor<1, 3> a = particle.semi_axes;
        build                = [a]() {
          const int tag = gmsh::model::occ::addSphere(0., 0., 0., 1.);
          gmsh::model::occ::dilate({{3, tag}}, 0., 0., 0., a[0], a[1], a[2]);
          gmsh::model::occ::synchronize();
        };
        std::ostringstream s;
        s << "an ellipsoid of diameters " << 2 * a[0] << ", " << 2 * a[1]
          << ", " << 2 * a[2] << " mm";
        what = s.str();
      }
    else
      {
        const SurfaceMesh &surface = *particle.surface;
        build                      = [&surface]() {
          // the closed triangulation as a discrete surface, split at sharp
          // edges into patches gmsh can parametrise and mesh again
          const int                tag = gmsh::model::addDiscreteEntity(2);
          std::vector<std::size_t> node_tags;
          std::vector<double>      coordinates;
          for (std::size_t v = 0; v < surface.vertices.size(); ++v)
            {
              node_tags.push_back(v + 1);
              for (unsigned int d = 0; d < 3; ++d)
                coordinates.push_back(surface.vertices[v][d]);
            }
          gmsh::model::mesh::addNodes(2, tag, node_tags, coordinates);
          std::vector<std::size_t> element_tags, element_nodes;
          for (std::size_t t = 0; t < surface.triangles.size(); ++t)
            {
              element_tags.push_back(t + 1);
              for (unsigned int k = 0; k < 3; ++k)
                element_nodes.push_back(surface.triangles[t][k] + 1);
            }
          gmsh::model::mesh::addElementsByType(tag,
                                               2,
                                               element_tags,
                                               element_nodes);
          gmsh::model::mesh::classifySurfaces(40. * numbers::PI / 180.,
                                              true,
                                              true,
                                              numbers::PI);
          gmsh::model::mesh::createGeometry();
          gmsh::vectorpair surfaces;
          gmsh::model::getEntities(surfaces, 2);
          std::vector<int> surface_tags;
          for (const auto &entity : surfaces)
            surface_tags.push_back(entity.second);
          const int loop = gmsh::model::geo::addSurfaceLoop(surface_tags);
          gmsh::model::geo::addVolume({loop});
          gmsh::model::geo::synchronize();
        };
        what = "the surface of '" + particle.surface_file + "'";
      }

    TetMesh mesh = mesh_in_own_model(spec, points, build, what);
    // into the global orientation; a rotation keeps the Jacobians positive
    for (Point<3> &v : mesh.vertices)
      v = Point<3>(particle.rotation * Tensor<1, 3>(v));
    return mesh;
  }
} // namespace densify
