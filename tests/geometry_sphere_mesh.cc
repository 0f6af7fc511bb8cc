// Test of mesh_sphere(): counts, surface, poles, volume, deal.II Jacobians.
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/geometry/sphere_mesher.h>

#include "test_utilities.h"
#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

using namespace densify;

using densify::testing::all_passed;
using densify::testing::yes;

namespace
{



  /// Six-fold signed volume of a tet of @p mesh.
  double
  volume6(const TetMesh &mesh, const std::array<unsigned int, 4> &c)
  {
    const Tensor<1, 3> e1 = mesh.vertices[c[1]] - mesh.vertices[c[0]];
    const Tensor<1, 3> e2 = mesh.vertices[c[2]] - mesh.vertices[c[0]];
    const Tensor<1, 3> e3 = mesh.vertices[c[3]] - mesh.vertices[c[0]];
    return scalar_product(e1, cross_product_3d(e2, e3));
  }



  /// The boundary triangles of @p mesh: faces that belong to one tet only.
  std::vector<std::array<unsigned int, 3>>
  boundary_triangles(const TetMesh &mesh)
  {
    std::map<std::array<unsigned int, 3>, unsigned int> count;
    for (const auto &c : mesh.cells)
      for (unsigned int skip = 0; skip < 4; ++skip)
        {
          std::array<unsigned int, 3> face;
          unsigned int                k = 0;
          for (unsigned int v = 0; v < 4; ++v)
            if (v != skip)
              face[k++] = c[v];
          std::sort(face.begin(), face.end());
          ++count[face];
        }
    std::vector<std::array<unsigned int, 3>> result;
    for (const auto &[face, n] : count)
      if (n == 1)
        result.push_back(face);
    return result;
  }



  /// Index of the vertex at @p p (to 1e-12), or -1.
  int
  find_vertex(const TetMesh &mesh, const Point<3> &p)
  {
    for (unsigned int i = 0; i < mesh.vertices.size(); ++i)
      if (mesh.vertices[i].distance(p) < 1e-12)
        return i;
    return -1;
  }



  /// Index of the vertex nearest to @p p.
  int
  nearest_vertex(const TetMesh &mesh, const Point<3> &p)
  {
    int best = 0;
    for (unsigned int i = 0; i < mesh.vertices.size(); ++i)
      if (mesh.vertices[i].distance(p) < mesh.vertices[best].distance(p))
        best = i;
    return best;
  }



  /// Shortest and longest edge of the tets that contain vertex @p v.
  std::pair<double, double>
  edge_range_at(const TetMesh &mesh, const int v)
  {
    double shortest = 1e300, longest = 0.;
    for (const auto &c : mesh.cells)
      if (std::find(c.begin(), c.end(), static_cast<unsigned int>(v)) !=
          c.end())
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int b = a + 1; b < 4; ++b)
            {
              const double l =
                mesh.vertices[c[a]].distance(mesh.vertices[c[b]]);
              shortest = std::min(shortest, l);
              longest  = std::max(longest, l);
            }
    return {shortest, longest};
  }



  /**
   * Largest relative gap (R - |centroid|) / R between the sphere and the
   * centroids of the boundary triangles within @p distance of a pole.
   */
  double
  max_gap_near_poles(const TetMesh &mesh, const double R, const double distance)
  {
    double gap = 0.;
    for (const auto &f : boundary_triangles(mesh))
      {
        const Point<3> centroid =
          (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) /
          3.;
        if (std::min(centroid.distance(Point<3>(0, 0, R)),
                     centroid.distance(Point<3>(0, 0, -R))) < distance)
          gap = std::max(gap, (R - centroid.norm()) / R);
      }
    return gap;
  }



  /// All checks of one sphere mesh; returns the sum of its tet volumes.
  double
  check_mesh(const std::string &name,
             const TetMesh     &mesh,
             const double       R,
             const unsigned int min_tets,
             const unsigned int max_tets)
  {
    const std::string p = name + ": ";
    std::cout << p << "tets in [" << min_tets << "," << max_tets << "]: "
              << yes(mesh.cells.size() >= min_tets &&
                     mesh.cells.size() <= max_tets)
              << std::endl;

    std::vector<bool> used(mesh.vertices.size(), false);
    bool              in_range = true;
    for (const auto &c : mesh.cells)
      for (const unsigned int v : c)
        if (v < used.size())
          used[v] = true;
        else
          in_range = false;
    std::cout << p << "vertex indices in range and every vertex used: "
              << yes(in_range &&
                     std::count(used.begin(), used.end(), false) == 0)
              << std::endl;

    bool   positive = true;
    double volume   = 0.;
    for (const auto &c : mesh.cells)
      {
        const double v6 = volume6(mesh, c);
        positive        = positive && v6 > 0.;
        volume += v6 / 6.;
      }
    std::cout << p
              << "det[x1-x0, x2-x0, x3-x0] > 0 for every tet: " << yes(positive)
              << std::endl;

    // The boundary must be a closed surface: every edge in two triangles.
    const auto boundary = boundary_triangles(mesh);
    std::map<std::pair<unsigned int, unsigned int>, unsigned int> edges;
    std::set<unsigned int> surface_vertices;
    for (const auto &f : boundary)
      for (unsigned int a = 0; a < 3; ++a)
        {
          surface_vertices.insert(f[a]);
          ++edges[{std::min(f[a], f[(a + 1) % 3]),
                   std::max(f[a], f[(a + 1) % 3])}];
        }
    bool closed = !boundary.empty();
    for (const auto &e : edges)
      closed = closed && e.second == 2;
    std::cout << p << "boundary is closed (every edge in 2 triangles): "
              << yes(closed) << std::endl;

    bool on_sphere = true, inside = true;
    for (unsigned int v = 0; v < mesh.vertices.size(); ++v)
      if (surface_vertices.count(v))
        on_sphere =
          on_sphere && std::abs(mesh.vertices[v].norm() - R) <= 1e-10 * R;
      else
        inside = inside && mesh.vertices[v].norm() < R * (1. - 1e-10);
    std::cout << p << "surface vertices on the sphere (1e-10 relative): "
              << yes(on_sphere) << std::endl;
    std::cout << p << "interior vertices inside the sphere: " << yes(inside)
              << std::endl;
    std::cout << p << "poles (0,0,+-R) are vertices: "
              << yes(find_vertex(mesh, Point<3>(0, 0, R)) >= 0 &&
                     find_vertex(mesh, Point<3>(0, 0, -R)) >= 0)
              << std::endl;

    const double exact = 4. / 3. * numbers::PI * R * R * R;
    std::cout << p << "volume within 2% of 4/3 pi R^3: "
              << yes(std::abs(volume - exact) <= 0.02 * exact) << std::endl;

    // The same mesh in deal.II: measure() is signed for tets, so a positive
    // measure means a positive Jacobian; check the Jacobian directly too.
    Triangulation<3>         tria;
    std::vector<CellData<3>> cells;
    for (const auto &c : mesh.cells)
      {
        CellData<3> cell(4);
        std::copy(c.begin(), c.end(), cell.vertices.begin());
        cells.push_back(cell);
      }
    tria.create_triangulation(mesh.vertices, cells, SubCellData());

    const MappingFE<3>     mapping(FE_SimplexP<3>(1));
    const FE_SimplexP<3>   fe(1);
    const QGaussSimplex<3> quadrature(1);
    FEValues<3>            fe_values(mapping, fe, quadrature, update_jacobians);
    bool                   measure_positive = true, jacobian_matches = true;
    double                 measure_sum = 0.;
    for (const auto &cell : tria.active_cell_iterators())
      {
        const double measure = cell->measure();
        measure_positive     = measure_positive && measure > 0.;
        measure_sum += measure;
        fe_values.reinit(cell);
        const double det = determinant(Tensor<2, 3>(fe_values.jacobian(0)));
        jacobian_matches =
          jacobian_matches && std::abs(det - 6. * measure) <= 1e-10 * det;
      }
    std::cout << p << "deal.II cells: "
              << yes(tria.n_active_cells() == mesh.cells.size())
              << ", every cell->measure() > 0: " << yes(measure_positive)
              << std::endl;
    std::cout << p << "sum of cell->measure() == sum of tet volumes: "
              << yes(std::abs(measure_sum - volume) <= 1e-12 * volume)
              << std::endl;
    std::cout << p << "MappingFE Jacobian determinant == 6 measure > 0: "
              << yes(jacobian_matches) << std::endl;
    return volume;
  }



  /// The measure deal.II gives a single tet with the given vertex order.
  double
  single_tet_measure(const std::array<unsigned int, 4> &order)
  {
    const std::vector<Point<3>> vertices = {Point<3>(0, 0, 0),
                                            Point<3>(1, 0, 0),
                                            Point<3>(0, 1, 0),
                                            Point<3>(0, 0, 1)};
    CellData<3>                 cell(4);
    std::copy(order.begin(), order.end(), cell.vertices.begin());
    Triangulation<3> tria;
    tria.create_triangulation(vertices, {cell}, SubCellData());
    return tria.begin_active()->measure();
  }



  /// Print the message of the std::runtime_error mesh_sphere(spec) throws.
  void
  expect_error(const std::string &what, const SphereMeshSpec &spec)
  {
    try
      {
        mesh_sphere(spec);
        std::cout << what << ": no error thrown: " << yes(false) << std::endl;
      }
    catch (const std::runtime_error &e)
      {
        std::cout << what << ": " << e.what() << std::endl;
      }
  }
} // namespace



int
main()
{
  std::cout << "deal.II measure of the reference tet (0,1,2,3): "
            << single_tet_measure({{0, 1, 2, 3}})
            << ", with vertices 2 and 3 swapped: "
            << single_tet_measure({{0, 1, 3, 2}}) << std::endl;

  const double   R = 1.25;
  SphereMeshSpec uniform_spec;
  uniform_spec.radius       = R;
  uniform_spec.element_size = 0.3;
  const TetMesh uniform     = mesh_sphere(uniform_spec);
  const double  uniform_volume =
    check_mesh("uniform h=0.3", uniform, R, 1000, 3000);

  SphereMeshSpec refined_spec        = uniform_spec;
  refined_spec.refined_element_size  = 0.05;
  refined_spec.growth                = 0.5;
  refined_spec.refinement_directions = {Tensor<1, 3>({0., 0., 2.}),
                                        Tensor<1, 3>({0., 0., -1.})};
  const TetMesh refined              = mesh_sphere(refined_spec);
  const double  refined_volume =
    check_mesh("refined at poles", refined, R, 1000, 6000);

  const int north = find_vertex(refined, Point<3>(0, 0, R));
  const int south = find_vertex(refined, Point<3>(0, 0, -R));
  std::cout << "refined at poles: shortest edge at each pole < 2 h_fine = 0.1: "
            << yes(north >= 0 && south >= 0 &&
                   edge_range_at(refined, north).first < 0.1 &&
                   edge_range_at(refined, south).first < 0.1)
            << std::endl;
  std::cout << "uniform h=0.3: shortest edge at the north pole > 0.1: "
            << yes(
                 edge_range_at(uniform, find_vertex(uniform, Point<3>(0, 0, R)))
                   .first > 0.1)
            << std::endl;
  const int equator = nearest_vertex(refined, Point<3>(R, 0, 0));
  std::cout << "refined at poles: the vertex nearest to (R,0,0) has an edge "
               "> 0.2 (coarse away from the poles): "
            << yes(edge_range_at(refined, equator).second > 0.2) << std::endl;
  std::cout << "refined at poles: boundary triangles within 0.3 of a pole "
               "are closer to the sphere than uniform ones: "
            << yes(max_gap_near_poles(refined, R, 0.3) <
                   0.5 * max_gap_near_poles(uniform, R, 0.3))
            << std::endl;
  const double exact = 4. / 3. * numbers::PI * R * R * R;
  std::cout << "volume errors of both below 2% and of equal size (within "
               "0.5% of each other): "
            << yes(std::abs(uniform_volume - exact) < 0.02 * exact &&
                   std::abs(refined_volume - exact) < 0.02 * exact &&
                   std::abs(refined_volume - uniform_volume) < 0.005 * exact)
            << std::endl;

  // One refinement point off the axes.
  SphereMeshSpec one_point        = refined_spec;
  one_point.refinement_directions = {Tensor<1, 3>({1., 1., 0.})};
  const TetMesh  skew             = mesh_sphere(one_point);
  const Point<3> target(R / std::sqrt(2.), R / std::sqrt(2.), 0.);
  double         nearest = 1e300, shortest = 1e300;
  for (const auto &c : skew.cells)
    for (unsigned int a = 0; a < 4; ++a)
      nearest = std::min(nearest, skew.vertices[c[a]].distance(target));
  for (const auto &c : skew.cells)
    {
      bool near = false;
      for (unsigned int a = 0; a < 4; ++a)
        near = near || skew.vertices[c[a]].distance(target) < 0.1;
      if (near)
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int b = a + 1; b < 4; ++b)
            shortest =
              std::min(shortest,
                       skew.vertices[c[a]].distance(skew.vertices[c[b]]));
    }
  std::cout << "refined towards (1,1,0): a vertex within 0.05 of the point "
               "and an edge < 0.1 near it: "
            << yes(nearest < 0.05 && shortest < 0.1) << std::endl;

  // Deterministic: the same spec gives the same mesh.
  const TetMesh again = mesh_sphere(refined_spec);
  std::cout << "same spec, same mesh (vertices and cells identical): "
            << yes(again.vertices == refined.vertices &&
                   again.cells == refined.cells)
            << std::endl;

  // Errors.
  SphereMeshSpec bad = uniform_spec;
  bad.radius         = -1.;
  expect_error("radius -1", bad);
  bad              = uniform_spec;
  bad.element_size = 0.;
  expect_error("element size 0", bad);
  bad                       = refined_spec;
  bad.refinement_directions = {Tensor<1, 3>()};
  expect_error("zero refinement direction", bad);
  bad                      = refined_spec;
  bad.refined_element_size = -0.1;
  expect_error("refined element size -0.1", bad);

  const TetMesh after = mesh_sphere(uniform_spec);
  std::cout << "gmsh still usable after the errors, same mesh as before: "
            << yes(after.vertices == uniform.vertices &&
                   after.cells == uniform.cells)
            << std::endl;

  // Somebody else's gmsh model stays current, and a gmsh::finalize() behind
  // the mesher's back (GridIn::read_msh() does one) does not break it.
  gmsh::model::add("user model");
  mesh_sphere(uniform_spec);
  std::string current;
  gmsh::model::getCurrent(current);
  std::cout << "the caller's current gmsh model is current again: "
            << yes(current == "user model") << std::endl;
  gmsh::finalize();
  const TetMesh after_finalize = mesh_sphere(uniform_spec);
  std::cout << "after gmsh::finalize(), gmsh is initialised again, same mesh: "
            << yes(after_finalize.vertices == uniform.vertices &&
                   after_finalize.cells == uniform.cells)
            << std::endl;

  return all_passed ? 0 : 1;
}
