// Measures of each particle in the current state (volume, mean
// displacement, rotation, mean stress), and the particles.csv writer.
#pragma once

#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <densify/geometry/particles.h>
#include <densify/material/material.h>
#include <densify/postprocess/material_points.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// Measures of one particle in the current state.
  struct ParticleMeasure
  {
    /// Current volume (mm^3).
    double volume = 0.;
    /// Volume-weighted mean displacement (mm).
    Tensor<1, 3> mean_displacement;
    /// Mean rigid rotation vector (rad; small-rotation measure): the
    /// w that best fits u = w x (X - centre) after the mean translation.
    Tensor<1, 3> rotation;
    /// Mean Cauchy stress over the current volume (MPa; by
    /// measure_particle_stresses(), else zero). By equilibrium it is the
    /// sum of the contact forces' moments x (x) f over the volume, so it
    /// vanishes for a free particle.
    Tensor<2, 3> mean_stress;
    /// Mean of the von Mises stress over the current volume (MPa): the
    /// intensity of the stress the particle holds, also where the mean stress
    /// vanishes (residual stress after ejection).
    double mean_von_mises = 0.;
  };

  /**
   * Measure every particle: one pass over the locally owned cells of
   * @p dof_handler (the displacement, FE_SimplexP of @p degree times 3) with
   * the Gauss rule of degree + 1, summed over @p comm; the result is on
   * every rank. @p solution must hold the entries of the locally relevant
   * DoFs. The cells' material id is the index into @p particles and
   * @p materials; the volume is the one the kinematics of the particle's law
   * sees (det F at finite strain, 1 + div u at small strain).
   */
  std::vector<ParticleMeasure>
  measure_particles(
    const DoFHandler<3>                                &dof_handler,
    const Mapping<3>                                   &mapping,
    const unsigned int                                  degree,
    const TrilinosWrappers::MPI::Vector                &solution,
    const std::vector<Particle>                        &particles,
    const std::vector<std::shared_ptr<const Material>> &materials,
    const MPI_Comm                                      comm);

  /**
   * Add each particle's mean stress and mean von Mises stress to
   * @p measures (index: material id of the cells, the particle): one pass
   * over the locally owned cells of @p dof_handler through @p points, each
   * point weighted by its current volume, summed over @p comm.
   */
  void
  measure_particle_stresses(const DoFHandler<3>          &dof_handler,
                            MaterialPoints               &points,
                            std::vector<ParticleMeasure> &measures,
                            const MPI_Comm                comm);

  /**
   * Writes particles.csv: a header line, then per load step one row per
   * particle (volume, initial volume, mean displacement, rotation, contact
   * partners, die contact, mean stress), flushed at once so that the file is
   * valid whenever a run stops.
   */
  class ParticleTableWriter
  {
  public:
    /// Open (truncate) @p filename and write the header; with @p append,
    /// append rows to the existing file (a resumed run; a file of an older
    /// Densify gets today's header, its rows padded with nan). Throws
    /// std::runtime_error if the header cannot be written.
    ParticleTableWriter(const std::string &filename, const bool append);

    /**
     * Append the rows of load step @p step: per particle p its measures
     * @p measures[p], initial volume @p initial_volumes[p], the number of
     * particles it touches @p partners[p] and whether the die wall pushes
     * on it (@p die_force[p] > 0). Returns "" or, if they cannot be written
     * (e.g. a full disk), the error naming the file and the cause, with the
     * file cut back to its complete rows.
     */
    std::string
    write(const unsigned int                  step,
          const std::vector<Particle>        &particles,
          const std::vector<ParticleMeasure> &measures,
          const std::vector<double>          &initial_volumes,
          const std::vector<unsigned int>    &partners,
          const std::vector<double>          &die_force);

    /// The header line (column names, comma-separated).
    static std::string
    header();

  private:
    std::string   filename;
    std::ofstream out;
  };
} // namespace densify
