// Explicit dynamics: a perfectly plastic J2 cylinder (Sn) upset by 30 %
// between frictionless rigid plates. The scene's explicit path on a mesh the
// Simulator cannot make (its particles are spheres): P1 tetrahedra of a
// cylinder, the nodal-averaged F-bar forces with one return mapping per cell,
// the lumped mass with selective mass scaling and its power-iteration
// calibration, the frictionless punch contact with its penalty chosen for
// the stable step, and the central-difference integrator with its smooth
// ramp of the upper punch. The plates leave the lateral expansion free, so
// the quasi-static answer is homogeneous uniaxial flow at the Kirchhoff yield
// stress: punch force F = sigma_y A0 H0 / H (A0 = V0 / H0) and plastic work
// sigma_y V0 (ln(H0 / H) - sigma_y / E) (the elastic axial log strain
// sigma_y / E is 0.2 % of ln(H0 / H) at the end), with H the specimen's
// current height. Both are required within 1 %: the force at the stations
// from 3 % height reduction on (the station force is the least-squares line
// through the forces of its interval, as in the Simulator, and the first
// interval holds the elastic rise and the onset of yield), the plastic work at
// every station; the energy balance within 1e-4 of the external work.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/assembly/lumped_mass.h>
#include <densify/assembly/nodal_averaging.h>
#include <densify/contact/tool_contact.h>
#include <densify/drivers/explicit_dynamics.h>
#include <densify/material/j2_plasticity.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <vector>

using namespace densify;

namespace
{
  using Vec = TrilinosWrappers::MPI::Vector;

  /// Radius and height of the cylinder (mm), and the height reduction.
  constexpr double radius = 1., H0 = 2., reduction = 0.3;

  /**
   * The cylinder between two frictionless punches as an ExplicitSystem, the
   * way the ExplicitDriver is one (source/drivers/explicit_driver.cc): internal
   * forces by the nodal-averaged F-bar with shared corners, every state
   * committed, the punches' contact forces as the external ones. The x and
   * y components of the vertices on the axis and the y component of those
   * on the half-plane y = 0, x > 0 are held (zero force): they remove the
   * rigid in-plane motions that frictionless plates leave free without
   * restraining the homogeneous lateral expansion.
   */
  class Upset : public ExplicitSystem
  {
  public:
    /// Set up on @p dof_handler (P1 vector); @p u is the displacement the
    /// integrator advances (read by update_mass()).
    Upset(const DoFHandler<3>                                &dof_handler,
          const std::vector<std::shared_ptr<const Material>> &materials,
          const Vec                                          &u)
      : dof_handler(dof_handler)
      , materials(materials)
      , mapping(FE_SimplexP<3>(1))
      , averaging(dof_handler, mapping)
      , lumped(dof_handler, materials, MassScaling::selective, 0.)
      , u(u)
      , committed(dof_handler.get_triangulation().n_active_cells() * 4)
      , trial(committed)
    {
      for (const auto &cell : dof_handler.active_cell_iterators())
        for (const unsigned int v : cell->vertex_indices())
          {
            const Point<3> &X = cell->vertex(v);
            if (std::abs(X[0]) < 1e-9 && std::abs(X[1]) < 1e-9)
              for (unsigned int c = 0; c < 2; ++c)
                held.push_back(cell->vertex_dof_index(v, c));
            else if (std::abs(X[1]) < 1e-9 && X[0] > 0.)
              held.push_back(cell->vertex_dof_index(v, 1));
            if (std::abs(X[2] - H0) < 1e-9)
              top.push_back(cell->vertex_dof_index(v, 2));
            else if (std::abs(X[2]) < 1e-9)
              bottom.push_back(cell->vertex_dof_index(v, 2));
          }
      for (std::vector<types::global_dof_index> *list : {&held, &top, &bottom})
        {
          std::sort(list->begin(), list->end());
          list->erase(std::unique(list->begin(), list->end()), list->end());
        }
    }

    /**
     * The lumped mass scaled so that the stable step reaches
     * @p required_step, with the cell bound calibrated as the Simulator
     * does, and the punches with the contact penalty that fits it.
     */
    void
    setup(const double required_step)
    {
      Vec mass;
      lumped.update(u, required_step, mass);
      lumped.calibrate(largest_frequency2(mass), 1.25, true);
      lumped.update(u, required_step, mass);
      const std::vector<double> penalty = lumped.contact_penalties({0.25});
      std::vector<RigidTool>    tools(2);
      tools[0].kind     = ToolKind::lower_punch;
      tools[0].position = 0.;
      tools[1].kind     = ToolKind::upper_punch;
      tools[1].position = H0;
      contact.setup(dof_handler,
                    tools,
                    std::vector<FrictionLaw>(2),
                    penalty,
                    QGaussSimplex<2>(2));
      contact.set_committed_solution(u);
      std::cout << "contact penalty " << std::setprecision(4) << penalty[0]
                << " MPa/mm, calibration " << lumped.calibration_factor()
                << ", added mass " << lumped.added_mass_fraction() << std::endl;
    }

    double
    update_mass(const double required_step, Vec &mass) override
    {
      return lumped.update(u, required_step, mass);
    }

    void
    forces(const Vec   &displacement,
           const double scene_time,
           const double scene_increment,
           const double dt,
           Vec         &internal,
           Vec         &external) override
    {
      const double position = H0 * (1. - reduction * scene_time);
      contact.set_tool_position(ToolKind::upper_punch, position);
      internal                  = 0.;
      const std::string failure = averaging.assemble(
        displacement, materials, &committed, &trial, internal, nullptr, true);
      if (!failure.empty())
        throw std::runtime_error(failure);
      internal.compress(VectorOperation::add);
      committed.swap(trial);
      external = 0.;
      const ToolContactResult result =
        contact.assemble_and_commit(mapping, displacement, external);
      external.compress(VectorOperation::add);
      for (const types::global_dof_index i : held)
        internal(i) = external(i) = 0.;

      // the punch's work along its travel (trapezoidal rule)
      const unsigned int upper =
        static_cast<unsigned int>(ToolKind::upper_punch);
      const double force = result.normal_force[upper];
      if (scene_increment > 0.)
        work += (last_force + force) / 2. * (last_position - position);
      last_force    = force;
      last_position = position;
      // time-weighted sums for the least-squares line through the forces
      // of an interval (as the Simulator's stations)
      const double lower =
        result.normal_force[static_cast<unsigned int>(ToolKind::lower_punch)];
      for (unsigned int k = 0; k < 3; ++k)
        sums[k] += dt * std::pow(scene_time, k);
      moments[0] += dt * force;
      moments[1] += dt * scene_time * force;
      moments[2] += dt * lower;
      moments[3] += dt * scene_time * lower;
    }

    double
    external_work() const override
    {
      return work;
    }

    /// Start a new interval of the force sums.
    void
    clear_sums()
    {
      std::fill(sums.begin(), sums.end(), 0.);
      std::fill(moments.begin(), moments.end(), 0.);
    }

    /// The upper (@p which = 0) or lower (1) punch force at scene time
    /// @p tau from the least-squares line over the interval.
    double
    fitted_force(const unsigned int which, const double tau) const
    {
      const double f0 = moments[2 * which], f1 = moments[2 * which + 1];
      const double det   = sums[0] * sums[2] - sums[1] * sums[1];
      const double slope = (sums[0] * f1 - sums[1] * f0) / det;
      return (f0 - sums[1] * slope) / sums[0] + tau * slope;
    }

    /// Current height: mean z of the top face minus that of the bottom.
    double
    height() const
    {
      double z_top = 0., z_bottom = 0.;
      for (const types::global_dof_index i : top)
        z_top += u(i);
      for (const types::global_dof_index i : bottom)
        z_bottom += u(i);
      return H0 + z_top / top.size() - z_bottom / bottom.size();
    }

    /// Plastic work (mJ): the corners' V/4 times the law's plastic work.
    double
    plastic_work() const
    {
      double w = 0.;
      for (const auto &cell : dof_handler.active_cell_iterators())
        for (unsigned int q = 0; q < 4; ++q)
          w += cell->measure() / 4. *
               materials[0]->plastic_work(
                 committed[cell->active_cell_index() * 4 + q]);
      return w;
    }

  private:
    const DoFHandler<3>                                &dof_handler;
    const std::vector<std::shared_ptr<const Material>> &materials;
    const MappingFE<3>                                  mapping;
    NodalAveraging                                      averaging;
    LumpedMass                                          lumped;
    ToolContact                                         contact;
    const Vec                                          &u;
    std::vector<MaterialState>                          committed, trial;
    std::vector<types::global_dof_index>                held, top, bottom;
    double                work = 0., last_force = 0., last_position = H0;
    std::array<double, 3> sums    = {{0., 0., 0.}};
    std::array<double, 4> moments = {{0., 0., 0., 0.}};

    /**
     * The largest squared frequency of the elastic mesh with @p mass, by a
     * power iteration on M^-1 K with K x a finite difference of the internal
     * forces at the virgin state (ExplicitDriver::largest_frequency2(); the J2
     * law stays elastic at these strains).
     */
    double
    largest_frequency2(const Vec &mass)
    {
      Vec x(mass), Kx(mass), f0(mass), v(mass);
      f0 = 0.;
      averaging.assemble(u, materials, nullptr, nullptr, f0, nullptr, true);
      f0.compress(VectorOperation::add);
      for (const auto &cell : dof_handler.active_cell_iterators())
        for (const unsigned int k : cell->vertex_indices())
          for (unsigned int c = 0; c < 3; ++c)
            {
              const Point<3> &X = cell->vertex(k);
              x(cell->vertex_dof_index(k, c)) =
                std::sin(1. + 7. * X[0] + 9. * X[1] + 11. * X[2] + c);
            }
      double omega2 = 0.;
      for (unsigned int it = 0; it < 40; ++it)
        {
          const double delta = 1e-8 / x.linfty_norm();
          v                  = u;
          v.add(delta, x);
          Kx = 0.;
          averaging.assemble(v, materials, nullptr, nullptr, Kx, nullptr, true);
          Kx.compress(VectorOperation::add);
          Kx -= f0;
          Kx /= delta;
          double xMx = 0.;
          for (unsigned int k = 0; k < x.locally_owned_size(); ++k)
            xMx += x.begin()[k] * mass.begin()[k] * x.begin()[k];
          omega2 = (x * Kx) / xMx;
          for (unsigned int k = 0; k < x.locally_owned_size(); ++k)
            x.begin()[k] = Kx.begin()[k] / mass.begin()[k];
          x /= x.linfty_norm();
        }
      return omega2;
    }
  };
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  // the cylinder: deal.II's hexahedra (axis x) refined once onto the
  // cylindrical surface, each split into 24 tetrahedra, turned to the z axis
  // with the bottom at z = 0
  Triangulation<3> hexahedra, tria;
  GridGenerator::subdivided_cylinder(hexahedra, 1, radius, H0 / 2.);
  hexahedra.refine_global(1);
  GridGenerator::convert_hypercube_to_simplex_mesh(hexahedra, tria);
  tria.reset_all_manifolds();
  tria.set_all_manifold_ids(numbers::flat_manifold_id);
  GridTools::transform(
    [](const Point<3> &p) { return Point<3>(p[1], p[2], p[0] + H0 / 2.); },
    tria);
  const FESystem<3> fe(FE_SimplexP<3>(1), 3);
  DoFHandler<3>     dof_handler(tria);
  dof_handler.distribute_dofs(fe);
  double V0 = 0.;
  for (const auto &cell : tria.active_cell_iterators())
    V0 += cell->measure();
  std::cout << "cylinder R = " << radius << " mm, H0 = " << H0
            << " mm: " << tria.n_active_cells() << " tetrahedra, "
            << dof_handler.n_dofs() << " DoFs, volume " << std::setprecision(5)
            << V0 << " mm^3" << std::endl;

  const J2Parameters parameters = material_preset("Sn");
  const std::vector<std::shared_ptr<const Material>> materials = {
    std::make_shared<J2Plasticity>(parameters)};
  const double sigma_y = parameters.sigma0;

  ExplicitParameters prm;
  prm.loading_time  = 1.;
  prm.n_steps       = 2000;
  prm.mass_scaling  = "selective";
  prm.ramp_fraction = 0.05;

  TrilinosWrappers::MPI::Vector u(dof_handler.locally_owned_dofs(),
                                  MPI_COMM_SELF);
  Upset                         system(dof_handler, materials, u);
  system.setup(prm.loading_time / prm.n_steps / prm.safety);
  ExplicitDynamics dynamics(prm, 1., MPI_COMM_SELF);
  dynamics.start(system, u, true);

  // 20 stations; the station's force is the least-squares line through the
  // forces of its interval (as the Simulator's), which cannot follow the
  // elastic rise and the onset of yield in the first interval (the first
  // 1.5 % of height reduction, inside the velocity ramp): the force is
  // checked from the second station on, the plastic work at every station
  const unsigned int n_stations  = 20;
  double             worst_force = 0., worst_work = 0., worst_balance = 0.;
  double             worst_lower = 0., last_kinetic = 0.;
  std::cout << "H/H0   force (N)  exact (N)  plastic work (mJ)  exact (mJ)"
            << std::endl;
  for (unsigned int s = 1; s <= n_stations; ++s)
    {
      const double tau = double(s) / n_stations;
      system.clear_sums();
      const ExplicitDynamics::Account a = dynamics.advance(system, u, tau);
      const double                    H = system.height();
      const double                    F = system.fitted_force(0, tau);
      const double                    F_lower = system.fitted_force(1, tau);
      const double                    F_exact = sigma_y * V0 / H;
      const double                    W       = system.plastic_work();
      const double                    W_exact =
        sigma_y * V0 * (std::log(H0 / H) - sigma_y / parameters.E);
      worst_work = std::max(worst_work, std::abs(W / W_exact - 1.));
      worst_balance =
        std::max(worst_balance,
                 std::abs(a.external_on_mesh - a.internal - a.kinetic) /
                   a.external_on_mesh);
      if (s > 1)
        {
          worst_force = std::max(worst_force, std::abs(F / F_exact - 1.));
          worst_lower = std::max(worst_lower, std::abs(F_lower / F - 1.));
        }
      if (s % 4 == 0)
        std::cout << std::fixed << std::setprecision(3) << H / H0 << "  "
                  << std::setprecision(1) << std::setw(9) << F << std::setw(11)
                  << F_exact << std::setprecision(2) << std::setw(19) << W
                  << std::setw(12) << W_exact << std::defaultfloat << std::endl;
      if (s == n_stations)
        {
          last_kinetic = a.kinetic / a.internal;
          std::cout << "explicit steps " << a.steps
                    << "; at the end plastic work / (sigma_y V0 ln(H0/H)) "
                    << std::fixed << std::setprecision(3)
                    << W / (sigma_y * V0 * std::log(H0 / H))
                    << std::defaultfloat << std::endl;
        }
    }
  std::cout << std::scientific << std::setprecision(1)
            << "largest relative error: force " << worst_force
            << ", plastic work " << worst_work << std::endl
            << "lower / upper punch force - 1: " << worst_lower
            << "; KE/IE at the end " << last_kinetic << std::defaultfloat
            << std::endl
            << "energy balance within 1e-4 of the external work: "
            << (worst_balance < 1e-4 ? "yes" : "no") << std::endl;
  const bool ok =
    worst_force < 1e-2 && worst_work < 1e-2 && worst_balance < 1e-4;
  std::cout << "force and plastic work within 1 % of exact: "
            << (ok ? "yes" : "no") << std::endl;
  return ok ? 0 : 1;
}
