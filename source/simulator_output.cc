// The Simulator's measures of the particles, its graphics and its warning
// about the element's health.
#include <densify/postprocess/material_points.h>
#include <densify/simulator.h>

#include <iomanip>

namespace densify
{
  std::vector<ParticleMeasure>
  Simulator::measure_particles(const bool with_stress) const
  {
    TrilinosWrappers::MPI::Vector ghosted(locally_owned,
                                          locally_relevant,
                                          comm);
    ghosted = solution;
    std::vector<ParticleMeasure> measures =
      densify::measure_particles(dof_handler,
                                 *mapping,
                                 prm.mesh.degree,
                                 ghosted,
                                 particles,
                                 particle_material,
                                 comm);
    if (with_stress)
      {
        MaterialPoints points(dof_handler,
                              *mapping,
                              prm.mesh.degree,
                              ghosted,
                              particle_material,
                              continuum->has_history() ?
                                &continuum->committed() :
                                nullptr,
                              continuum->states_per_cell(),
                              continuum->fbar());
        measure_particle_stresses(dof_handler, points, measures, comm);
      }
    return measures;
  }



  std::vector<double>
  Simulator::particle_volumes() const
  {
    std::vector<double> volume;
    for (const ParticleMeasure &m : measure_particles())
      volume.push_back(m.volume);
    return volume;
  }



  std::vector<Tensor<1, 3>>
  Simulator::particle_mean_displacements() const
  {
    std::vector<Tensor<1, 3>> mean;
    for (const ParticleMeasure &m : measure_particles())
      mean.push_back(m.mean_displacement);
    return mean;
  }



  void
  Simulator::write_graphics(const unsigned int                  step,
                            const double                        time,
                            const std::vector<ParticleMeasure> &measures)
  {
    TimerOutput::Scope t(timer, "Output: graphics");
    update_ghosts();
    graphics.write(step,
                   time,
                   dof_handler,
                   *mapping,
                   prm.mesh.degree,
                   solution_ghosted,
                   particle_material,
                   continuum->has_history() ? &continuum->committed() : nullptr,
                   continuum->states_per_cell(),
                   continuum->fbar(),
                   tool_contact.get(),
                   particle_contact.get(),
                   effects.any_friction(),
                   &measures,
                   prm.output.directory,
                   comm);
  }



  void
  Simulator::warn_cell_volume(const unsigned int        step,
                              const SmallestCellVolume &smallest)
  {
    // once per run: the ratio stays low once a cell has collapsed
    if (cell_volume_warned || !(smallest.ratio < 0.2))
      return;
    cell_volume_warned = true;
    pcout << "  warning: a cell's volume fell to V/V0 = "
          << std::setprecision(3) << smallest.ratio << " (below 0.2) at step "
          << step << " in particle " << smallest.particle << " at ("
          << smallest.centre
          << ") mm (reference position; printed once, statistics.csv has "
             "min_cell_volume_ratio of every step): its forces are biased; "
             "raise Mesh/Cell volume barrier from "
          << prm.mesh.cell_volume_barrier << std::endl;
  }
} // namespace densify
