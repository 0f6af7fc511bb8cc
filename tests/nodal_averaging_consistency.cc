// Nodal averaging (P1 F-bar): on a homogeneous deformation its internal
// forces equal the plain ones (Fbar = F when J is uniform); on a random
// deformation of a small tetrahedral block its tangent matches central
// finite differences of its internal forces and is symmetric. For the
// finite-strain J2 law (Sn, plastic at every corner) and small-strain
// linear elasticity, without and with the stabilisation of the cells' own
// volume change (weight 0.05). The explicit method's force kernel
// (NodalAveraging::forces()) gives the Newton residual's forces, and the
// same plastic strains, to round-off from a committed plastic state, and
// the same to the last bit when it updates the states in place.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>

#include <deal.II/distributed/shared_tria.h>

#include <densify/assembly/all_values.h>
#include <densify/assembly/nodal_averaging.h>
#include <densify/material/j2_plasticity.h>

#include "test_utilities.h"

#include <cmath>
#include <iostream>
#include <random>
#include <sstream>

using namespace densify;

namespace
{
  using Vec = TrilinosWrappers::MPI::Vector;

  /// Standard output on rank 0 only.
  std::ostream &
  out()
  {
    static std::ostringstream sink;
    return Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0 ? std::cout :
                                                                   sink;
  }

  /// A P1 block [0,1]^3 of tetrahedra with the remedy set up.
  struct Block
  {
    /// @p alpha: the stabilisation weight of the cells' own volume change;
    /// @p barrier: the barrier against crushed cells (CellVolumeBarrier).
    explicit Block(const double             alpha   = 0.,
                   const CellVolumeBarrier &barrier = CellVolumeBarrier())
      : tria(MPI_COMM_WORLD,
             Triangulation<3>::none,
             false,
             parallel::shared::Triangulation<3>::partition_metis)
      , fe(FE_SimplexP<3>(1), 3)
      , mapping(FE_SimplexP<3>(1))
      , dof_handler(tria)
    {
      GridGenerator::subdivided_hyper_cube_with_simplices(tria, 3);
      dof_handler.distribute_dofs(fe);
      owned = dof_handler.locally_owned_dofs();
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      averaging = std::make_unique<NodalAveraging>(dof_handler,
                                                   mapping,
                                                   std::vector<double>{alpha});
      averaging->set_cell_volume_barrier(barrier);
      TrilinosWrappers::SparsityPattern sp(owned, MPI_COMM_WORLD);
      DoFTools::make_sparsity_pattern(dof_handler,
                                      sp,
                                      AffineConstraints<double>(),
                                      false,
                                      Utilities::MPI::this_mpi_process(
                                        MPI_COMM_WORLD));
      averaging->add_sparsity(sp);
      sp.compress();
      tangent.reinit(sp);
      committed.assign(tria.n_active_cells() * 4, MaterialState());
      trial = committed;
    }

    /// Displacement u = (F0 - I) X + amplitude * random (all DoFs).
    Vec
    displacement(const Tensor<2, 3> &F0,
                 const double        amplitude,
                 const unsigned int  seed = 7) const
    {
      std::vector<double> noise(dof_handler.n_dofs()),
        values(dof_handler.n_dofs());
      std::mt19937                           random(seed);
      std::uniform_real_distribution<double> uniform(-1., 1.);
      for (double &v : noise)
        v = amplitude * uniform(random);
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            {
              const auto [c, v]    = fe.system_to_component_index(i);
              const Tensor<1, 3> X = cell->vertex(v);
              values[dofs[i]] =
                (F0 - unit_symmetric_tensor<3>())[c] * X + noise[dofs[i]];
            }
        }
      Vec u(owned, MPI_COMM_WORLD);
      for (const auto i : owned)
        u(i) = values[i];
      u.compress(VectorOperation::insert);
      return u;
    }

    /// Internal forces with the remedy (and its tangent into tangent).
    Vec
    forces(const Vec &u, const Material &material, const bool with_matrix)
    {
      Vec ghosted(owned, relevant, MPI_COMM_WORLD);
      ghosted = u;
      Vec residual(owned, MPI_COMM_WORLD);
      if (with_matrix)
        tangent = 0;
      const std::vector<std::shared_ptr<const Material>> materials = {
        std::shared_ptr<const Material>(&material, [](const Material *) {})};
      const std::string failure =
        averaging->assemble(ghosted,
                            materials,
                            material.needs_history() ? &committed : nullptr,
                            material.needs_history() ? &trial : nullptr,
                            residual,
                            with_matrix ? &tangent : nullptr);
      if (!failure.empty())
        throw std::runtime_error(failure);
      residual.compress(VectorOperation::add);
      if (with_matrix)
        tangent.compress(VectorOperation::add);
      return residual;
    }

    /// Internal forces by the explicit method's kernel,
    /// NodalAveraging::forces(), on plain arrays: the trial states into
    /// trial, or with @p in_place the states of *in_place updated in place,
    /// as the explicit method's steps do, and their corners filled after.
    Vec
    explicit_forces(const Vec                  &u,
                    const Material             &material,
                    std::vector<MaterialState> *in_place = nullptr)
    {
      Vec ghosted(owned, relevant, MPI_COMM_WORLD);
      ghosted = u;
      AllValues values;
      values.gather(ghosted);
      Vec         residual(owned, MPI_COMM_WORLD);
      LocalForces local;
      local.start(residual);
      const std::vector<std::shared_ptr<const Material>> materials = {
        std::shared_ptr<const Material>(&material, [](const Material *) {})};
      const bool                  history = material.needs_history();
      std::vector<MaterialState> *old     = in_place ? in_place : &committed;
      std::vector<MaterialState> *now     = in_place ? in_place : &trial;
      const std::string           failure = averaging->forces(values,
                                                    materials,
                                                    history ? old : nullptr,
                                                    history ? now : nullptr,
                                                    local);
      if (!failure.empty())
        throw std::runtime_error(failure);
      if (history && in_place)
        averaging->fill_shared_corners(*in_place);
      local.finish(residual);
      residual.compress(VectorOperation::add);
      return residual;
    }

    /// Plain internal forces (P(F) at the four points of each cell).
    Vec
    plain_forces(const Vec &u, const Material &material) const
    {
      Vec ghosted(owned, relevant, MPI_COMM_WORLD);
      ghosted = u;
      Vec                                  residual(owned, MPI_COMM_WORLD);
      const QGaussSimplex<3>               quadrature(2);
      FEValues<3>                          fe_values(mapping,
                            fe,
                            quadrature,
                            update_gradients | update_JxW_values);
      const FEValuesExtractors::Vector     displacement(0);
      std::vector<Tensor<2, 3>>            grad_u(quadrature.size());
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      Vector<double>                       cell_residual(dofs.size());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            fe_values.reinit(cell);
            fe_values[displacement].get_function_gradients(ghosted, grad_u);
            cell_residual = 0;
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              {
                Tensor<2, 3>  P;
                Tensor<4, 3>  A;
                MaterialState scratch;
                material.evaluate(unit_symmetric_tensor<3>() + grad_u[q],
                                  material.needs_history() ? &committed[0] :
                                                             nullptr,
                                  material.needs_history() ? &scratch : nullptr,
                                  P,
                                  A);
                for (unsigned int i = 0; i < dofs.size(); ++i)
                  cell_residual(i) += P[fe.system_to_component_index(i).first] *
                                      fe_values.shape_grad(i, q) *
                                      fe_values.JxW(q);
              }
            cell->get_dof_indices(dofs);
            residual.add(dofs, cell_residual);
          }
      residual.compress(VectorOperation::add);
      return residual;
    }

    parallel::shared::Triangulation<3> tria;
    FESystem<3>                        fe;
    MappingFE<3>                       mapping;
    DoFHandler<3>                      dof_handler;
    IndexSet                           owned, relevant;
    std::unique_ptr<NodalAveraging>    averaging;
    TrilinosWrappers::SparseMatrix     tangent;
    std::vector<MaterialState>         committed, trial;
  };

  void
  check(Block &block, const Material &material, const std::string &label)
  {
    using testing::yes;
    out() << label << " (" << material.name() << ")" << std::endl;
    Tensor<2, 3> F0;
    F0[0][0] = 0.93;
    F0[1][1] = 1.02;
    F0[2][2] = 1.04;
    F0[0][1] = 0.03;
    F0[2][0] = -0.02;

    // homogeneous: Fbar = F, so the forces are the plain ones
    {
      const Vec    u     = block.displacement(F0, 0.);
      Vec          diff  = block.forces(u, material, false);
      const Vec    plain = block.plain_forces(u, material);
      const double scale = plain.l2_norm();
      diff -= plain;
      const double error = diff.l2_norm() / scale;
      out() << "  homogeneous: forces equal the plain ones: "
            << yes(error < 1e-10) << " (relative difference < 1e-10)"
            << std::endl;
      std::cerr << label << " homogeneous difference " << error << std::endl;
    }

    // random: tangent against central differences, and symmetry
    {
      const Vec u = block.displacement(F0, 0.02);
      Vec       d = block.displacement(unit_symmetric_tensor<3>(), 0.01, 8);
      block.forces(u, material, true);
      unsigned int plastic = 0;
      for (const MaterialState &s : block.trial)
        plastic += (s.eps_p > 0 ? 1 : 0);
      plastic = Utilities::MPI::sum(plastic, MPI_COMM_WORLD);
      if (material.needs_history())
        out() << "  random: plastic at " << plastic << " of "
              << 4 * block.tria.n_active_cells() << " corners" << std::endl;
      Vec Kd(block.owned, MPI_COMM_WORLD);
      block.tangent.vmult(Kd, d);

      const double h  = 1e-5;
      Vec          up = u, um = u;
      up.add(h, d);
      um.add(-h, d);
      Vec fd = block.forces(up, material, false);
      fd -= block.forces(um, material, false);
      fd *= 1. / (2 * h);
      fd -= Kd;
      const double error = fd.l2_norm() / Kd.l2_norm();
      out() << "  tangent = central differences of the forces: "
            << yes(error < 1e-6) << " (relative error < 1e-6)" << std::endl;

      // e^T K d = d^T K e for a second direction e
      const Vec e = block.displacement(unit_symmetric_tensor<3>(), 0.03, 9);
      Vec       Ke(block.owned, MPI_COMM_WORLD);
      block.tangent.vmult(Ke, e);
      const double asymmetry =
        std::abs(e * Kd - d * Ke) / (Kd.l2_norm() * e.l2_norm());
      out() << "  tangent symmetric: " << yes(asymmetry < 1e-12)
            << " (relative asymmetry < 1e-12)" << std::endl;
      std::cerr << label << " fd error " << error << " asymmetry " << asymmetry
                << std::endl;
    }

    // the explicit kernel against the assembly of the Newton residual, from
    // a committed state of the random deformation above to a second one
    {
      block.forces(block.displacement(F0, 0.02), material, false);
      block.committed = block.trial;
      Tensor<2, 3> F1 = F0;
      F1[0][0] -= 0.02;
      F1[1][2] += 0.01;
      const Vec u         = block.displacement(F1, 0.02, 11);
      Vec       reference = block.forces(u, material, false);
      const std::vector<MaterialState> reference_states = block.trial;
      const Vec    kernel = block.explicit_forces(u, material);
      const double scale  = reference.l2_norm();
      reference -= kernel;
      const double error       = reference.l2_norm() / scale;
      double       state_error = 0., eps_max = 0.;
      for (unsigned int k = 0; k < block.trial.size(); ++k)
        {
          state_error = std::max(state_error,
                                 std::abs(block.trial[k].eps_p -
                                          reference_states[k].eps_p));
          eps_max     = std::max(eps_max, reference_states[k].eps_p);
        }
      state_error = Utilities::MPI::max(state_error, MPI_COMM_WORLD);
      eps_max     = Utilities::MPI::max(eps_max, MPI_COMM_WORLD);
      out() << "  explicit kernel = implicit assembly, from a stored plastic "
               "state: "
            << yes(error < 1e-10) << " (relative difference < 1e-10)"
            << std::endl;
      if (material.needs_history())
        out() << "  explicit kernel's plastic strains = the assembly's: "
              << yes(state_error <= 1e-10 * eps_max) << " (to 1e-10 of "
              << "the largest)" << std::endl;
      std::cerr << label << " explicit kernel difference " << error
                << " plastic strain difference " << state_error << " of "
                << eps_max << std::endl;

      // the same step with the states updated in place: the same forces
      // and, once the corners are filled, the same states at every corner
      // of the owned cells, to the last bit
      std::vector<MaterialState> states = block.committed;
      Vec in_place = block.explicit_forces(u, material, &states);
      in_place -= kernel;
      bool same_states = true;
      for (const auto &cell : block.dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() && material.needs_history())
          for (unsigned int v = 0; v < 4; ++v)
            {
              const std::size_t k = cell->active_cell_index() * 4 + v;
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  same_states = same_states && states[k].Cp_inv[i][j] ==
                                                 block.trial[k].Cp_inv[i][j];
              same_states =
                same_states && states[k].eps_p == block.trial[k].eps_p;
            }
      same_states = Utilities::MPI::min(same_states ? 1 : 0, MPI_COMM_WORLD);
      out() << "  explicit kernel in place = with separate states: "
            << yes(in_place.linfty_norm() == 0. && same_states)
            << " (forces and states identical)" << std::endl;
      block.committed.assign(block.committed.size(), MaterialState());
    }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  Block                            block;
  out() << "P1 block: " << block.tria.n_active_cells() << " tetrahedra, "
        << block.dof_handler.n_dofs() << " DoFs" << std::endl;
  check(block, J2Plasticity(material_preset("Sn")), "finite strain");
  check(block, LinearElastic(43120., 0.3, "Sn"), "small strain");
  // with the stabilisation of the cells' own volume change
  Block stabilised(0.05);
  check(stabilised,
        J2Plasticity(material_preset("Sn")),
        "finite strain, cell volume weight 0.05");
  check(stabilised,
        LinearElastic(43120., 0.3, "Sn"),
        "small strain, cell volume weight 0.05");
  // with the barrier against crushed cells, its band narrowed to
  // [0.97, 1/0.97] so that the random deformations take many cells beyond
  // it (the barrier's forces change the block's by more than a tenth)
  {
    const J2Plasticity sn(material_preset("Sn"));
    CellVolumeBarrier  barrier;
    barrier.log_limit = std::log(0.97);
    barrier.stiffness = {sn.bulk_modulus()};
    Block        with_barrier(0.05, barrier);
    Tensor<2, 3> F0;
    F0[0][0]                              = 0.93;
    F0[1][1]                              = 1.02;
    F0[2][2]                              = 1.04;
    const TrilinosWrappers::MPI::Vector u = with_barrier.displacement(F0, 0.02);
    TrilinosWrappers::MPI::Vector changed = with_barrier.forces(u, sn, false);
    const TrilinosWrappers::MPI::Vector without =
      stabilised.forces(u, sn, false);
    changed -= without;
    out() << "cell volume barrier 0.97 acts on the random deformation: "
          << testing::yes(changed.l2_norm() > 0.1 * without.l2_norm())
          << std::endl;
    check(with_barrier, sn, "finite strain, cell volume weight 0.05, barrier");
  }
  out() << (testing::all_passed ? "all checks passed" : "FAILED") << std::endl;
  return testing::all_passed ? 0 : 1;
}
