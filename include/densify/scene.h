// The scene of a run as read from the parameters: particles, tool positions,
// load history.
#pragma once

#include <densify/contact/rigid_tools.h>
#include <densify/geometry/particles.h>
#include <densify/parameters.h>

#include <array>
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
    /// Sideways (x) upper punch displacement against time (s, mm).
    std::vector<std::pair<double, double>> lateral_table;
    /// Body force on every particle (N/mm^3) and its factor against time.
    Tensor<1, 3>                           body_force;
    std::vector<std::pair<double, double>> body_force_table;
    /// Friction coefficient of each tool, by ToolKind.
    std::array<double, n_tool_kinds> tool_friction = {{0., 0., 0.}};
  };

  /**
   * Build the scene from @p prm and check it: particle data, materials,
   * particles inside the container and not overlapping, the punch table.
   * Throws std::runtime_error with a one-line message naming the parameter.
   */
  Scene
  build_scene(const Parameters &prm);

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
