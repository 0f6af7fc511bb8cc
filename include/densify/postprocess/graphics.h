// Graphics of the load steps: one .pvtu per written step (displacement,
// stress, pressure, plastic strain, contact fields) and the .pvd listing them.
#pragma once

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <densify/contact/particle_contact.h>
#include <densify/contact/tool_contact.h>
#include <densify/material/j2_plasticity.h>
#include <densify/material/material.h>
#include <densify/postprocess/particle_measures.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace densify
{
  using namespace dealii;

  class NodalAveraging;

  /**
   * Writes the graphics of a run into its output directory:
   * solution_NNNNN.pvtu (with one .vtu per rank) for a load step, and
   * solution.pvd listing every step written so far with its time. The
   * fields are the displacement; lumped L2 projections onto P1 of the von
   * Mises stress, the pressure -tr(sigma)/3 and the equivalent plastic
   * strain (with a history) at the material points; the contact pressure
   * and, with friction, the accumulated slip and the stick/slip status on
   * the surface; the signed gap of each vertex to the nearest tool; the
   * particle id and the MPI rank of each cell, and its particle's mean
   * pressure and mean von Mises stress.
   */
  class GraphicsWriter
  {
  public:
    /// The .pvd's records: time and .pvtu file name of each written step.
    using Records = std::vector<std::pair<double, std::string>>;

    /**
     * Write the .pvtu of load step @p step at @p time into @p directory and
     * rewrite its solution.pvd (through a temporary file, so that the .pvd
     * is always complete). Collective over @p comm; throws
     * std::runtime_error on every rank, naming the file and the cause, if a
     * rank cannot write.
     *
     * @param dof_handler The displacement (FESystem(FE_SimplexP(@p degree),
     *   3)) on a triangulation every rank holds.
     * @param mapping The mapping of the cells.
     * @param degree The polynomial degree of the displacement.
     * @param solution The displacement with ghost entries (those the contact
     *   fields need; all DoFs with particle contact).
     * @param materials The material of each particle (index: material id).
     * @param history The committed quadrature-point history (index: active
     *   cell index * @p history_per_cell + point or corner), or nullptr
     *   without one (then there is no plastic_strain field).
     * @param history_per_cell Material states per cell in @p history.
     * @param nodal_averaging The nodal-averaged F-bar, or nullptr: with it
     *   the material is evaluated at Fbar of each cell corner with that
     *   corner's history.
     * @param tool_contact The tools (gap and contact fields), or nullptr
     *   without tools (then the gap is 0).
     * @param particle_contact The particle contact (contact fields), or
     *   nullptr without one.
     * @param friction Whether friction acts anywhere (the slip and
     *   stick_slip fields).
     * @param measures Each particle's measures with its mean stresses
     *   (measure_particle_stresses()), written as the cell fields
     *   particle_mean_pressure and particle_mean_von_mises, or nullptr
     *   (no such fields).
     * @param directory The output directory.
     * @param comm The communicator of the triangulation.
     */
    void
    write(const unsigned int                                  step,
          const double                                        time,
          const DoFHandler<3>                                &dof_handler,
          const Mapping<3>                                   &mapping,
          const unsigned int                                  degree,
          const TrilinosWrappers::MPI::Vector                &solution,
          const std::vector<std::shared_ptr<const Material>> &materials,
          const std::vector<MaterialState>                   *history,
          const unsigned int                                  history_per_cell,
          const NodalAveraging                               *nodal_averaging,
          const ToolContact                                  *tool_contact,
          const ParticleContact                              *particle_contact,
          const bool                                          friction,
          const std::vector<ParticleMeasure>                 *measures,
          const std::string                                  &directory,
          const MPI_Comm                                      comm);

    /// The records of the steps written so far (for checkpoints).
    const Records &
    records() const
    {
      return pvd_records;
    }

    /// Replace the records (a checkpoint's, on resumption).
    void
    set_records(const Records &records)
    {
      pvd_records = records;
    }

  private:
    /// See records().
    Records pvd_records;
  };
} // namespace densify
