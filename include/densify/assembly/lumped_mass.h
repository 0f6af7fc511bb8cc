// The lumped mass of explicit dynamics, its mass scaling, the stable time
// step and the contact penalty that fits it.
#pragma once

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/dofs/dof_handler.h>

#include <densify/assembly/all_values.h>
#include <densify/assembly/cell_volume_barrier.h>
#include <densify/material/material.h>

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

namespace densify
{
  using namespace dealii;

  /// How explicit dynamics raises densities to reach a target time step.
  enum class MassScaling
  {
    /// Physical densities.
    none,
    /// Every element by the one factor the smallest stable step needs.
    uniform,
    /// Each element only as far as its own stable step needs.
    selective
  };

  /**
   * Row-sum lumped mass of linear tetrahedra (V_e rho_e f_e / 4 on each
   * corner and component, f_e the mass-scaling factor of the cell) and the
   * stable time step of central differences with it.
   *
   * The stable step of a cell is bounded from below by
   * dt_e = 1 / sqrt(k_e / (rho_e f_e)) with k_e = min(M G, 3 K G_max):
   * M = lambda + 2 mu, K the bulk modulus, G = sum_a |grad N_a|^2 and G_max
   * the largest eigenvalue of sum_a grad N_a grad N_a^T in the current
   * configuration. For any corner displacements v, eps:D:eps <= k_e |v|^2,
   * so the largest eigenvalue of M_lumped^-1 K_e is at most 4 k_e / rho_e
   * f_e, and the largest frequency of the mesh at most that of its
   * stiffest cell (doc/theory.md). The contact
   * springs add omega_c^2 = 2 r eps A_i / m_i at a surface vertex i (A_i its
   * share of the surface, r = max(1, tangential / normal penalty)); the
   * stable step is 2 / sqrt(omega_e,max^2 + omega_c,max^2).
   *
   * Works on the locally owned cells of a parallel::shared triangulation;
   * every query returns the same value on every rank.
   */
  class LumpedMass
  {
  public:
    /**
     * @p materials by cell material id (particle); @p tangential_ratio the
     * friction's tangential over normal penalty (0 without friction);
     * @p cell_volume_weights the F-bar's stabilisation weight per material
     * id (NodalAveraging; empty: 0). Throws std::runtime_error if the element
     * is not linear or a material has no density.
     */
    LumpedMass(const DoFHandler<3>                                &dof_handler,
               const std::vector<std::shared_ptr<const Material>> &materials,
               const MassScaling                                   scaling,
               const double               tangential_ratio,
               const std::vector<double> &cell_volume_weights = {});

    /**
     * At displacement @p u (with the values of every DoF of the locally
     * owned cells) recompute each cell's stable step and, with mass scaling,
     * raise the scaling factors (never lower them while @p required_step
     * stays) so that the stable step of the whole mesh with its contact
     * springs is at least @p required_step; then write the lumped mass into
     * @p mass (locally owned entries). Returns the stable step (s). A
     * @p required_step other than the last one first scales every factor by
     * the square of their ratio (at least 1): the mass a step needs goes
     * with its square (Explicit/Step profile).
     */
    double
    update(const TrilinosWrappers::MPI::Vector &u,
           const double                         required_step,
           TrilinosWrappers::MPI::Vector       &mass);

    /**
     * The contact penalty (MPa/mm) of each particle p that makes the
     * stiffest contact spring's squared frequency @p stiffness[p] times the
     * cells' largest one, with the mass of the last update(). Later updates
     * include these springs in the stable step.
     */
    std::vector<double>
    contact_penalties(const std::vector<double> &stiffness);

    /**
     * The largest squared frequency of the elements with the mass of the
     * last update() as the cell bound gives it (1/s^2), for calibrate().
     */
    double
    bound_frequency2() const
    {
      return omega_bound2;
    }

    /**
     * Calibrate the cell bound by a measured largest squared frequency
     * @p omega2 of the mesh (the assembled elements with the mass of the
     * last update()): from now on the stable step and the mass scaling use
     * margin * omega2 / bound_frequency2() (at most 1) times the bound. The
     * cell bound is safe but, measured on meshes of spheres, 3-4 times too
     * small a step; the calibration keeps its dependence on each cell's
     * current shape. With @p restart the mass scaling starts afresh from the
     * calibrated bound (at the start of a run); without, the scaling factors
     * are kept and can only grow (during a run, so that no mass is taken
     * away from moving nodes). Recompute the mass (update()) afterwards.
     */
    void
    calibrate(const double omega2, const double margin, const bool restart);

    /**
     * The product @p Kx of the elastic stiffness of the cells in their
     * current configuration (displacement @p u, ghosted) with @p x
     * (ghosted): small-strain Hooke's law with each particle's moduli on
     * the deformed cells, the volume change averaged over each vertex's
     * patch and blended with the cell's own by its stabilisation weight as
     * in the nodal-averaged F-bar (section "Volumetric locking" of
     * doc/theory.md), the stiffness that decides the stable step. It
     * holds no stress: the plastic deformation does not enter as elastic
     * strain, as it would with the finite-strain law on the total
     * deformation.
     */
    void
    stiffness_product(const TrilinosWrappers::MPI::Vector &u,
                      const TrilinosWrappers::MPI::Vector &x,
                      TrilinosWrappers::MPI::Vector       &Kx) const;

    /// Restore a calibration factor saved from calibration_factor().
    void
    set_calibration_factor(const double saved)
    {
      calibration = saved;
    }

    /// The calibration factor (1: none).
    double
    calibration_factor() const
    {
      return calibration;
    }

    /// Added mass over physical mass of the whole mesh (0 without scaling).
    double
    added_mass_fraction() const
    {
      return added_fraction;
    }

    /// Total mass (t).
    double
    total_mass() const
    {
      return mass_total;
    }

    /// The lowest compression-mode frequency pi c / D over the particles
    /// (rad/s), with the scaled mass: the reference of the damping ratio.
    double
    lowest_frequency(const std::vector<double> &diameters) const;

    /// Mass-scaling factor of each cell (by active cell index; 1 on cells
    /// owned elsewhere), for checkpoints.
    const std::vector<double> &
    scaling_factors() const
    {
      return factor;
    }

    /// Include the barrier against crushed cells (NodalAveraging) in
    /// stiffness_product().
    void
    set_cell_volume_barrier(const CellVolumeBarrier &barrier)
    {
      volume_barrier = barrier;
    }

    /// Restore factors saved from scaling_factors() (same mesh), raised for
    /// the required step @p required_step (s) of update(), whose lumped mass
    /// was @p mass (the locally owned entries): the next update() takes the
    /// contact springs' share from it.
    void
    set_scaling_factors(const std::vector<double> &saved,
                        const double               required_step,
                        const std::vector<double> &mass)
    {
      factor      = saved;
      factor_step = required_step;
      if (last_mass.locally_owned_size() == mass.size())
        std::copy(mass.begin(), mass.end(), last_mass.begin());
    }

  private:
    const DoFHandler<3> *dof_handler;
    /// The locally owned DoFs.
    const IndexSet                                      owned;
    const std::vector<std::shared_ptr<const Material>> &materials;
    /// Per material id the F-bar's stabilisation weight alpha (NodalAveraging).
    std::vector<double> cell_volume_weights;
    /// The barrier against crushed cells (off by default).
    CellVolumeBarrier volume_barrier;
    const MassScaling scaling;
    /// max(1, tangential / normal penalty).
    const double spring_ratio;
    /// The required step the factors were last raised for (s; 0: none).
    double factor_step = 0.;
    /// Per active cell: mass-scaling factor, and the stable step with
    /// factor 1 at the last update.
    std::vector<double> factor, step_unscaled;
    /// The fixed data of a locally owned cell for update(): its active cell
    /// index and material id, the DoFs of its vertices (vertex by vertex,
    /// components in order), its reference corners and volume.
    struct OwnedCell
    {
      unsigned int                            index, material;
      std::array<types::global_dof_index, 12> dofs;
      std::array<Point<3>, 4>                 corners;
      double                                  volume;
    };
    std::vector<OwnedCell> owned_cells;
    /// update()'s plain arrays of the displacement and of the masses.
    AllValues   displacement;
    LocalForces mass_sums;
    /// Share of the surface area of each vertex DoF (component 0; mm^2).
    TrilinosWrappers::MPI::Vector area;
    /// The lumped mass of the last update.
    TrilinosWrappers::MPI::Vector last_mass;
    /// Contact penalty per particle (empty until contact_penalties()).
    std::vector<double> penalty;
    double              added_fraction = 0., mass_total = 0.;
    /// Squared-frequency calibration of the cell bound, and the bound's
    /// largest squared frequency at the last update.
    double calibration = 1., omega_bound2 = 0.;
    /// Per particle: total scaled mass and the mass-weighted mean of
    /// M / (rho f), the squared wave speed.
    std::vector<double> particle_mass, particle_wave_speed2;

    /// Largest squared contact-spring frequency with the mass @p mass.
    double
    contact_frequency2(const TrilinosWrappers::MPI::Vector &mass) const;
  };



  /**
   * Explicit/Contact stiffness for a particle of material @p material: the
   * number @p setting, or for "auto" the material's initial yield stress
   * over its Young's modulus divided by 1.44e-4, at least 1 and at most 100
   * (1 for a law that does not yield). The penalty's penetration at a
   * contact pressure of a few yield stresses is then alike, relative to the
   * element, in every material: 1.44e-4 gives tin (sigma0/E = 7.2e-4) the
   * factor 5 that keeps its explicit light layer within 1 % of the implicit
   * run up to 95 % relative density (doc/verification.md, "Pressed to
   * 95 %"). @p setting must have passed check_parameters().
   */
  double
  explicit_contact_stiffness(const std::string &setting,
                             const Material    &material);
} // namespace densify
