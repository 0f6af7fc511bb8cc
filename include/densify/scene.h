// The scene of a run as read from the parameters: particles, tool positions,
// load history.
#pragma once

#include <densify/contact/rigid_tools.h>
#include <densify/geometry/particles.h>
#include <densify/parameters.h>

#include <array>
#include <limits>
#include <utility>
#include <vector>

namespace densify
{
  /// Everything about a scene that is known before meshing.
  struct Scene
  {
    /// The particles (from Particles/Centres or the particle file).
    std::vector<Particle> particles;
    /// Height of the upper punch face at t = 0 (mm).
    double upper_initial = 0.;
    /// Downward punch displacement against time (s, mm).
    std::vector<std::pair<double, double>> punch_table;
    /// The upper punch's target force against time (s, N), one table per
    /// force window (empty: none).
    std::vector<std::vector<std::pair<double, double>>> force_table;
    /// Sideways (x) upper punch displacement against time (s, mm).
    std::vector<std::pair<double, double>> lateral_table;
    /// Upward lower punch displacement against time (s, mm).
    std::vector<std::pair<double, double>> lower_table;
    /// The lower punch's target (upward) force against time (s, N), one
    /// table per force window (empty: none).
    std::vector<std::vector<std::pair<double, double>>> lower_force_table;
    /// Upward die displacement against time (s, mm).
    std::vector<std::pair<double, double>> die_table;
    /// Height of the die's top edge (mm; infinity: none).
    double die_top = std::numeric_limits<double>::infinity();
    /// Body force on every particle (N/mm^3) and its factor against time.
    Tensor<1, 3>                           body_force;
    std::vector<std::pair<double, double>> body_force_table;
  };

  /**
   * Build the scene from @p prm and check it: particle data, materials,
   * particles inside the container and not overlapping, the punch table.
   * Throws std::runtime_error with a one-line message naming the parameter.
   */
  Scene
  build_scene(const Parameters &prm);

  /// The size of a scene's mesh, estimated before meshing.
  struct MeshEstimate
  {
    /// Number of tetrahedra of all particles.
    double elements = 0.;
    /// Memory of a run (bytes), roughly.
    double bytes = 0.;
    /// Distinct meshes: sphere diameters, each meshed once, and every
    /// particle of another shape.
    unsigned int distinct_diameters = 0;
  };

  /**
   * Estimate the mesh of @p particles from the element sizes of @p prm
   * (about 5.9 tetrahedra per h^3 of volume, more around the refinement
   * points) and the memory of a run on it.
   */
  MeshEstimate
  estimate_mesh(const Parameters &prm, const std::vector<Particle> &particles);

  /// @p n rounded to a whole number ("1234"), or as "1.2e+15" if huge.
  std::string
  format_count(const double n);

  /**
   * Throw std::runtime_error with a one-line message if @p estimate exceeds
   * Mesh/Maximum elements.
   */
  void
  check_mesh_size(const Parameters &prm, const MeshEstimate &estimate);

  /**
   * Throw std::runtime_error with a one-line message if Mesh/Element size
   * exceeds the smallest particle's diameter (gmsh cannot mesh a sphere with
   * larger elements).
   */
  void
  check_element_size(const Parameters            &prm,
                     const std::vector<Particle> &particles);

  /**
   * Give the particles the materials of the mixture @p fractions
   * ("name:fraction, ..."; fractions >= 0 summing to 1): round(fraction * N)
   * particles each (largest remainders first), which ones drawn by a shuffle
   * seeded with @p seed. Throws std::runtime_error with a one-line message on
   * bad input.
   */
  void
  draw_materials(const std::string     &fractions,
                 const unsigned int     seed,
                 std::vector<Particle> &particles);
} // namespace densify
