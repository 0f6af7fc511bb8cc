// One triangulation holding every particle, with no vertex shared between
// particles.
#pragma once

#include <deal.II/grid/tria.h>

#include <densify/geometry/particles.h>
#include <densify/geometry/sphere_mesher.h>

#include <vector>

namespace densify
{
  /**
   * Build the multi-body triangulation: each particle is meshed by
   * mesh_particle() (sphere meshes are cached by diameter, so equal spheres
   * are meshed once and translated; every ellipsoid and surface particle is
   * meshed on its own), and the union of all vertices and cells is handed
   * to Triangulation::create_triangulation() directly (not
   * merge_triangulations(), which would glue touching particles). Cell
   * material_id = particle index. @p spec.radius is ignored (taken from each
   * particle). @p tria may be a parallel::shared::Triangulation.
   */
  void
  build_multi_body_triangulation(const std::vector<Particle> &particles,
                                 const SphereMeshSpec        &spec,
                                 Triangulation<3>            &tria);
} // namespace densify
