// Test of build_multi_body_triangulation(): separate bodies, ids, volumes.
#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <deal.II/grid/tria.h>

#include <deal.II/distributed/shared_tria.h>

#include <densify/geometry/multi_body_mesh.h>

#include "test_utilities.h"

#include <cmath>
#include <iostream>
#include <string>

using namespace densify;

using densify::testing::all_passed;
using densify::testing::yes;

namespace
{



  /// Sum of the tet volumes of @p mesh.
  double
  mesh_volume(const TetMesh &mesh)
  {
    double volume = 0.;
    for (const auto &c : mesh.cells)
      {
        const Tensor<1, 3> e1 = mesh.vertices[c[1]] - mesh.vertices[c[0]];
        const Tensor<1, 3> e2 = mesh.vertices[c[2]] - mesh.vertices[c[0]];
        const Tensor<1, 3> e3 = mesh.vertices[c[3]] - mesh.vertices[c[0]];
        volume += scalar_product(e1, cross_product_3d(e2, e3)) / 6.;
      }
    return volume;
  }



  /**
   * Check a multi-body triangulation of @p particles against the single
   * sphere meshes: vertex and cell counts, per-particle cells, volumes and
   * centroids, boundary ids and that no two particles are neighbours.
   */
  void
  check_bodies(ConditionalOStream          &out,
               const std::string           &name,
               const std::vector<Particle> &particles,
               const SphereMeshSpec        &spec,
               const Triangulation<3>      &tria)
  {
    std::vector<TetMesh> meshes;
    std::size_t          n_vertices = 0, n_cells = 0;
    for (const Particle &p : particles)
      {
        SphereMeshSpec s = spec;
        s.radius         = 0.5 * p.diameter;
        meshes.push_back(mesh_sphere(s));
        n_vertices += meshes.back().vertices.size();
        n_cells += meshes.back().cells.size();
      }
    out << name << ": n_vertices == sum over particles (nothing merged): "
        << yes(tria.n_vertices() == n_vertices) << std::endl;
    out << name << ": n_active_cells == sum over particles: "
        << yes(tria.n_active_cells() == n_cells) << std::endl;

    std::vector<unsigned int> cells_of(particles.size(), 0);
    std::vector<double>       volume_of(particles.size(), 0.);
    std::vector<Point<3>>     moment_of(particles.size());
    bool                      ids_valid = true, no_contact = true;
    bool                      boundary_ids_zero = true;
    for (const auto &cell : tria.active_cell_iterators())
      {
        const unsigned int id = cell->material_id();
        if (id >= particles.size())
          {
            ids_valid = false;
            continue;
          }
        ++cells_of[id];
        volume_of[id] += cell->measure();
        moment_of[id] += cell->measure() * cell->center();
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            boundary_ids_zero =
              boundary_ids_zero && cell->face(f)->boundary_id() == 0;
          else
            no_contact = no_contact && cell->neighbor(f)->material_id() == id;
      }
    out << name << ": every material id is a particle index: " << yes(ids_valid)
        << std::endl;
    out << name
        << ": no face between cells of different particles: " << yes(no_contact)
        << ", boundary ids all 0: " << yes(boundary_ids_zero) << std::endl;

    for (unsigned int i = 0; i < particles.size(); ++i)
      {
        const double d     = particles[i].diameter;
        const double exact = numbers::PI * d * d * d / 6.;
        // gmsh's sphere meshes miss about 0.35 (h/R)^2 of the volume
        // (R = 1.25, h = 0.3: 1.8%; R = 0.75: 5.8%).
        const double   h_over_R  = spec.element_size / (0.5 * d);
        const double   tolerance = 0.45 * h_over_R * h_over_R;
        const double   mesh      = mesh_volume(meshes[i]);
        const Point<3> centroid  = moment_of[i] / volume_of[i];
        out << name << ": particle " << i << " (d = " << d
            << "): cells == its sphere mesh: "
            << yes(cells_of[i] == meshes[i].cells.size())
            << ", volume == its sphere mesh: "
            << yes(std::abs(volume_of[i] - mesh) <= 1e-12 * mesh)
            << ", within 0.45 (h/R)^2 of pi d^3/6: "
            << yes(std::abs(volume_of[i] - exact) <= tolerance * exact)
            << ", centroid within 0.01 mm of the centre: "
            << yes(centroid.distance(particles[i].centre) < 0.01) << std::endl;
      }
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  ConditionalOStream               out(std::cout,
                         Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0);

  // Two spheres touching pole to pole at (0,0,2.5), and a third one 0.5 mm
  // beside the first.
  std::vector<Particle> particles(3);
  particles[0].centre = Point<3>(0., 0., 1.25);
  particles[1].centre = Point<3>(0., 0., 3.75);
  particles[2].centre = Point<3>(3., 0., 1.25);
  for (Particle &p : particles)
    p.diameter = 2.5;

  SphereMeshSpec spec;
  spec.element_size = 0.3;

  Triangulation<3> tria;
  build_multi_body_triangulation(particles, spec, tria);
  check_bodies(out, "serial", particles, spec, tria);

  unsigned int at_contact = 0;
  for (unsigned int v = 0; v < tria.n_vertices(); ++v)
    if (tria.get_vertices()[v].distance(Point<3>(0., 0., 2.5)) < 1e-12)
      ++at_contact;
  out << "serial: vertices at the contact point (0,0,2.5): " << at_contact
      << std::endl;
  all_passed = all_passed && at_contact == 2;

  // Two diameters: each is meshed once (cache) and the counts still match.
  std::vector<Particle> mixed = particles;
  mixed[1].diameter           = 1.5;
  mixed[1].centre             = Point<3>(0., 0., 3.25);
  Triangulation<3> mixed_tria;
  build_multi_body_triangulation(mixed, spec, mixed_tria);
  check_bodies(out, "two diameters", mixed, spec, mixed_tria);

  // The same on a shared triangulation partitioned by METIS.
  parallel::shared::Triangulation<3> shared(
    MPI_COMM_WORLD,
    Triangulation<3>::none,
    false,
    parallel::shared::Triangulation<3>::partition_metis);
  build_multi_body_triangulation(particles, spec, shared);
  check_bodies(out, "shared", particles, spec, shared);
  const unsigned int owned =
    Utilities::MPI::sum(shared.n_locally_owned_active_cells(), MPI_COMM_WORLD);
  out << "shared: n_active_cells == serial n_active_cells: "
      << yes(shared.n_active_cells() == tria.n_active_cells())
      << ", locally owned cells add up to it: "
      << yes(owned == shared.n_active_cells()) << std::endl;
  out << "shared: n_global_active_cells == serial n_active_cells: "
      << yes(shared.n_global_active_cells() == tria.n_active_cells())
      << std::endl;

  // Every rank must agree.
  const unsigned int n_failed =
    Utilities::MPI::sum(all_passed ? 0u : 1u, MPI_COMM_WORLD);
  out << "all checks passed on every rank: " << yes(n_failed == 0) << std::endl;
  return n_failed == 0 ? 0 : 1;
}
