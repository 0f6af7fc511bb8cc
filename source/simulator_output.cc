// The Simulator's graphics and its warning about the element's health.
#include <densify/postprocess/material_points.h>
#include <densify/simulator.h>

#include <iomanip>

namespace densify
{
  void
  Simulator::write_graphics(const unsigned int                  step,
                            const double                        time,
                            const std::vector<ParticleMeasure> &measures)
  {
    TimerOutput::Scope t(timer, "Output: graphics");
    system.update_ghosts();
    graphics.write(step,
                   time,
                   system.dof_handler,
                   *system.mapping,
                   prm.mesh.degree,
                   system.solution_ghosted,
                   system.particle_material,
                   system.continuum->has_history() ?
                     &system.continuum->committed() :
                     nullptr,
                   system.continuum->states_per_cell(),
                   system.continuum->fbar(),
                   system.tool_contact.get(),
                   system.particle_contact.get(),
                   system.effects.any_friction(),
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
