// The lumped mass of explicit dynamics, its mass scaling, the stable time
// step and the contact penalty that fits it.
#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <densify/assembly/lumped_mass.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// Volume and shape gradients of a linear tetrahedron with corners
    /// @p x (a volume <= 0 for an inverted one, the gradients then unset).
    double
    tetrahedron_gradients(const std::array<Point<3>, 4> &x,
                          std::array<Tensor<1, 3>, 4>   &g)
    {
      Tensor<2, 3> J;
      for (unsigned int d = 0; d < 3; ++d)
        for (unsigned int e = 0; e < 3; ++e)
          J[e][d] = x[d + 1][e] - x[0][e];
      const double det = determinant(J);
      if (!(det > 0.))
        return det / 6.;
      // grad N_a = J^-T grad_ref N_a, grad_ref N_0 = -(1,1,1)
      const Tensor<2, 3> J_inv_T = transpose(invert(J));
      g[0]                       = Tensor<1, 3>();
      for (unsigned int a = 1; a < 4; ++a)
        {
          Tensor<1, 3> e;
          e[a - 1] = 1.;
          g[a]     = J_inv_T * e;
          g[0] -= g[a];
        }
      return det / 6.;
    }

    /// Volume, sum of the squared shape gradients G = sum_a |g_a|^2 and
    /// the largest eigenvalue of sum_a g_a g_a^T of a linear tetrahedron
    /// with corners @p x.
    std::array<double, 3>
    tetrahedron_measures(const std::array<Point<3>, 4> &x)
    {
      std::array<Tensor<1, 3>, 4> g;
      const double                V = tetrahedron_gradients(x, g);
      if (!(V > 0.))
        return {{V,
                 std::numeric_limits<double>::infinity(),
                 std::numeric_limits<double>::infinity()}};
      SymmetricTensor<2, 3> GG;
      for (const unsigned int a : {1u, 2u, 3u, 0u})
        GG += symmetrize(outer_product(g[a], g[a]));
      return {{V, trace(GG), eigenvalues(GG)[0]}};
    }
  } // namespace



  LumpedMass::LumpedMass(
    const DoFHandler<3>                                &dof_handler,
    const std::vector<std::shared_ptr<const Material>> &materials,
    const MassScaling                                   scaling,
    const double                                        tangential_ratio,
    const std::vector<double>                          &cell_volume_weights)
    : dof_handler(&dof_handler)
    , owned(dof_handler.locally_owned_dofs())
    , materials(materials)
    , cell_volume_weights(cell_volume_weights)
    , scaling(scaling)
    , spring_ratio(std::max(1., tangential_ratio))
    , factor(dof_handler.get_triangulation().n_active_cells(), 1.)
    , step_unscaled(factor.size(), std::numeric_limits<double>::infinity())
  {
    if (dof_handler.get_fe().degree != 1)
      throw std::runtime_error(
        "Solver/Method = explicit needs Mesh/Polynomial degree = 1 (the "
        "row-sum lumped mass of quadratic tetrahedra has negative corner "
        "masses)");
    for (const auto &m : materials)
      if (!(m->density() > 0.))
        throw std::runtime_error(
          "Solver/Method = explicit needs a mass density: set "
          "Material/Density for the material 'custom'");

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          OwnedCell c;
          c.index    = cell->active_cell_index();
          c.material = cell->material_id();
          for (const unsigned int v : cell->vertex_indices())
            {
              c.corners[v] = cell->vertex(v);
              for (unsigned int d = 0; d < 3; ++d)
                c.dofs[3 * v + d] = cell->vertex_dof_index(v, d);
            }
          c.volume = cell->measure();
          owned_cells.push_back(c);
        }

    // each vertex's share of the particle surface (a third of each
    // boundary triangle), on the reference configuration
    const MPI_Comm comm = dof_handler.get_communicator();
    area.reinit(owned, comm);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto         face = cell->face(f);
              const Tensor<1, 3> n =
                cross_product_3d(face->vertex(1) - face->vertex(0),
                                 face->vertex(2) - face->vertex(0));
              for (unsigned int v = 0; v < 3; ++v)
                {
                  // the face's vertex as a vertex of the cell, for its DoF
                  for (const unsigned int w : cell->vertex_indices())
                    if (cell->vertex_index(w) == face->vertex_index(v))
                      area(cell->vertex_dof_index(w, 0)) += n.norm() / 6.;
                }
            }
    area.compress(VectorOperation::add);
  }



  double
  LumpedMass::update(const TrilinosWrappers::MPI::Vector &u,
                     const double                         required_step,
                     TrilinosWrappers::MPI::Vector       &mass)
  {
    const MPI_Comm     comm    = dof_handler->get_communicator();
    const unsigned int n_parts = materials.size();
    // 1. the unscaled stable step of every owned cell in the current
    //    configuration
    std::vector<double> volume(factor.size(), 0.);
    displacement.gather(u);
    for (const OwnedCell &c : owned_cells)
      {
        std::array<Point<3>, 4> x = c.corners;
        for (unsigned int v = 0; v < 4; ++v)
          for (unsigned int d = 0; d < 3; ++d)
            x[v][d] += displacement[c.dofs[3 * v + d]];
        const auto [V, G, G_max] = tetrahedron_measures(x);
        (void)V;
        const Material &m = *materials[c.material];
        // the smaller of the two bounds of the largest eigenvalue of the
        // element stiffness per volume (doc/theory.md)
        const double stiffness =
          std::min(m.p_wave_modulus() * G, 3. * m.bulk_modulus() * G_max);
        step_unscaled[c.index] = 1. / std::sqrt(stiffness / m.density());
        volume[c.index]        = c.volume;
      }

    // 2. the contact springs' share: with omega_c^2 = kappa omega_e^2 the
    //    stable step is the elements' one over sqrt(1 + kappa); with mass
    //    scaling the factors then follow from the elements alone
    //    (omega_c^2 falls with the mass as omega_e^2 does)
    double min_unscaled = std::numeric_limits<double>::infinity();
    for (const OwnedCell &c : owned_cells)
      min_unscaled =
        std::min(min_unscaled,
                 step_unscaled[c.index] * std::sqrt(factor[c.index]));
    min_unscaled        = Utilities::MPI::min(min_unscaled, comm);
    double spring_share = 1.;
    if (!penalty.empty() && last_mass.size() > 0)
      {
        const double omega_e2 =
          calibration * 4. / (min_unscaled * min_unscaled);
        spring_share = 1. + contact_frequency2(last_mass) / omega_e2;
      }
    if (scaling != MassScaling::none && required_step > 0.)
      {
        // another required step (Explicit/Step profile): the factors it
        // needs follow as its square
        if (factor_step > 0. && required_step != factor_step)
          {
            const double s =
              (required_step / factor_step) * (required_step / factor_step);
            for (const OwnedCell &c : owned_cells)
              factor[c.index] = std::max(1., factor[c.index] * s);
          }
        factor_step = required_step;
        // each cell's stable step needs to reach required_step * share,
        // the calibrated bound's
        const double target =
          required_step * std::sqrt(spring_share * calibration);
        double needed = 1.;
        for (const OwnedCell &c : owned_cells)
          {
            const double r = target / step_unscaled[c.index];
            needed         = std::max(needed, r * r);
            if (scaling == MassScaling::selective)
              factor[c.index] = std::max(factor[c.index], r * r);
          }
        if (scaling == MassScaling::uniform)
          {
            needed = Utilities::MPI::max(needed, comm);
            for (const OwnedCell &c : owned_cells)
              factor[c.index] = std::max(factor[c.index], needed);
          }
      }

    // 3. the lumped mass and the measures of the scaled mesh
    mass.reinit(owned, comm);
    mass_sums.start(mass);
    double              physical = 0., scaled = 0.;
    double              min_step = std::numeric_limits<double>::infinity();
    std::vector<double> part_mass(n_parts, 0.), part_c2(n_parts, 0.);
    for (const OwnedCell &c : owned_cells)
      {
        const unsigned int e   = c.index;
        const unsigned int p   = c.material;
        const Material    &m   = *materials[p];
        const double       m_e = m.density() * factor[e] * volume[e];
        for (const types::global_dof_index dof : c.dofs)
          mass_sums.add(dof, m_e / 4.);
        physical += m.density() * volume[e];
        scaled += m_e;
        part_mass[p] += m_e;
        part_c2[p] += m_e * m.p_wave_modulus() / (m.density() * factor[e]);
        min_step = std::min(min_step, step_unscaled[e] * std::sqrt(factor[e]));
      }
    mass_sums.finish(mass);
    mass.compress(VectorOperation::add);
    physical = Utilities::MPI::sum(physical, comm);
    scaled   = Utilities::MPI::sum(scaled, comm);
    min_step = Utilities::MPI::min(min_step, comm);
    Utilities::MPI::sum(part_mass, comm, part_mass);
    Utilities::MPI::sum(part_c2, comm, part_c2);
    particle_mass        = part_mass;
    particle_wave_speed2 = part_c2;
    for (unsigned int p = 0; p < n_parts; ++p)
      if (part_mass[p] > 0.)
        particle_wave_speed2[p] /= part_mass[p];
    added_fraction = scaled / physical - 1.;
    mass_total     = scaled;
    last_mass      = mass;

    omega_bound2          = 4. / (min_step * min_step);
    const double omega_e2 = calibration * omega_bound2;
    const double omega_c2 = penalty.empty() ? 0. : contact_frequency2(mass);
    return 2. / std::sqrt(omega_e2 + omega_c2);
  }



  void
  LumpedMass::calibrate(const double omega2,
                        const double margin,
                        const bool   restart)
  {
    // the measured frequency over the raw cell bound of the last update()
    if (omega_bound2 > 0. && omega2 > 0.)
      calibration = std::min(1., margin * omega2 / omega_bound2);
    if (restart)
      std::fill(factor.begin(), factor.end(), 1.);
  }



  void
  LumpedMass::stiffness_product(const TrilinosWrappers::MPI::Vector &u,
                                const TrilinosWrappers::MPI::Vector &x,
                                TrilinosWrappers::MPI::Vector       &Kx) const
  {
    // small-strain Hooke on the current cells with the volume change
    // averaged over each vertex's patch as the nodal-averaged F-bar does:
    // the elastic stiffness of unloading from the current state (no stress,
    // so the plastic deformation does not count as elastic strain)
    const MPI_Comm                comm = dof_handler->get_communicator();
    TrilinosWrappers::MPI::Vector sums(owned, comm), volumes(owned, comm);
    const unsigned int            n_cells = factor.size();
    std::vector<double>           V(n_cells, 0.);
    std::vector<std::array<Tensor<1, 3>, 4>> g(n_cells);
    std::vector<Tensor<2, 3>>                grad(n_cells);
    std::array<Point<3>, 4>                  corner;
    AllValues                                u_values, x_values;
    u_values.gather(u);
    x_values.gather(x);
    LocalForces sum_values, volume_values;
    sum_values.start(sums);
    volume_values.start(volumes);
    for (const OwnedCell &c : owned_cells)
      {
        const unsigned int e = c.index;
        for (unsigned int v = 0; v < 4; ++v)
          {
            corner[v] = c.corners[v];
            for (unsigned int d = 0; d < 3; ++d)
              corner[v][d] += u_values[c.dofs[3 * v + d]];
          }
        V[e] = tetrahedron_gradients(corner, g[e]);
        if (!(V[e] > 0.))
          continue;
        for (unsigned int v = 0; v < 4; ++v)
          for (unsigned int d = 0; d < 3; ++d)
            grad[e][d] += x_values[c.dofs[3 * v + d]] * g[e][v];
        for (unsigned int v = 0; v < 4; ++v)
          {
            sum_values.add(c.dofs[3 * v], V[e] * trace(grad[e]));
            volume_values.add(c.dofs[3 * v], V[e]);
          }
      }
    sum_values.finish(sums);
    volume_values.finish(volumes);
    sums.compress(VectorOperation::add);
    volumes.compress(VectorOperation::add);
    TrilinosWrappers::MPI::Vector sums_ghosted(x), volumes_ghosted(x);
    sums_ghosted    = sums;
    volumes_ghosted = volumes;
    AllValues patch_sums, patch_volumes;
    patch_sums.gather(sums_ghosted);
    patch_volumes.gather(volumes_ghosted);

    Kx = 0.;
    LocalForces products;
    products.start(Kx);
    for (const OwnedCell &c : owned_cells)
      {
        const unsigned int e = c.index;
        if (!(V[e] > 0.))
          continue;
        const Material &m  = *materials[c.material];
        const double    K  = m.bulk_modulus();
        const double    mu = 0.75 * (m.p_wave_modulus() - K);
        // the mean of the corners' patch-averaged volume changes,
        // blended with the cell's own by the stabilisation weight
        double theta = 0.;
        for (unsigned int v = 0; v < 4; ++v)
          {
            const types::global_dof_index i = c.dofs[3 * v];
            theta += patch_sums[i] / patch_volumes[i] / 4.;
          }
        const double alpha = c.material < cell_volume_weights.size() ?
                               cell_volume_weights[c.material] :
                               0.;
        theta              = (1. - alpha) * theta + alpha * trace(grad[e]);
        // a cell beyond the barrier's band adds its own volume change
        // with the barrier's stiffness (CellVolumeBarrier)
        const double k_barrier =
          volume_barrier.excess(std::log(V[e] / c.volume)) != 0. ?
            volume_barrier.modulus(c.material) :
            0.;
        const SymmetricTensor<2, 3> eps = symmetrize(grad[e]);
        const SymmetricTensor<2, 3> sigma =
          2. * mu * deviator(eps) +
          (K * theta + k_barrier * trace(grad[e])) * unit_symmetric_tensor<3>();
        for (unsigned int v = 0; v < 4; ++v)
          {
            const Tensor<1, 3> f = V[e] * (sigma * g[e][v]);
            for (unsigned int d = 0; d < 3; ++d)
              products.add(c.dofs[3 * v + d], f[d]);
          }
      }
    products.finish(Kx);
    Kx.compress(VectorOperation::add);
  }



  double
  LumpedMass::contact_frequency2(
    const TrilinosWrappers::MPI::Vector &mass) const
  {
    // per surface vertex 2 r eps_p A_i / m_i, the largest over the mesh
    double omega2 = 0.;
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            const types::global_dof_index i = cell->vertex_dof_index(v, 0);
            if (!owned.is_element(i) || area(i) == 0.)
              continue;
            omega2 = std::max(omega2,
                              2. * spring_ratio * penalty[cell->material_id()] *
                                area(i) / mass(i));
          }
    return Utilities::MPI::max(omega2, dof_handler->get_communicator());
  }



  std::vector<double>
  LumpedMass::contact_penalties(const std::vector<double> &stiffness)
  {
    Assert(last_mass.size() > 0, ExcMessage("update() first"));
    AssertDimension(stiffness.size(), materials.size());
    const MPI_Comm comm = dof_handler->get_communicator();
    // the elements' largest squared frequency, and per particle the largest
    // A_i / m_i of its surface vertices
    double              min_step = std::numeric_limits<double>::infinity();
    std::vector<double> ratio(materials.size(), 0.);
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int e = cell->active_cell_index();
          min_step =
            std::min(min_step, step_unscaled[e] * std::sqrt(factor[e]));
          for (const unsigned int v : cell->vertex_indices())
            {
              const types::global_dof_index i = cell->vertex_dof_index(v, 0);
              if (owned.is_element(i))
                ratio[cell->material_id()] =
                  std::max(ratio[cell->material_id()], area(i) / last_mass(i));
            }
        }
    min_step = Utilities::MPI::min(min_step, comm);
    Utilities::MPI::max(ratio, comm, ratio);
    const double omega_e2 = calibration * 4. / (min_step * min_step);
    penalty.assign(materials.size(), 0.);
    for (unsigned int p = 0; p < materials.size(); ++p)
      if (ratio[p] > 0.)
        penalty[p] = stiffness[p] * omega_e2 / (2. * spring_ratio * ratio[p]);
    return penalty;
  }



  double
  LumpedMass::lowest_frequency(const std::vector<double> &diameters) const
  {
    double omega = std::numeric_limits<double>::infinity();
    for (unsigned int p = 0; p < diameters.size() && p < particle_mass.size();
         ++p)
      if (particle_mass[p] > 0.)
        omega = std::min(omega,
                         numbers::PI * std::sqrt(particle_wave_speed2[p]) /
                           diameters[p]);
    return omega;
  }


  double
  explicit_contact_stiffness(const std::string &setting,
                             const Material    &material)
  {
    const std::string k = Utilities::trim(setting);
    if (k != "auto")
      return Utilities::string_to_double(k);
    // sigma0 / E of tin over the factor it needs (doc/verification.md)
    constexpr double reference_ratio = 1.44e-4;
    const double     ratio =
      material.initial_yield_stress() / material.youngs_modulus();
    if (!std::isfinite(ratio))
      return 1.;
    return std::min(100., std::max(1., ratio / reference_ratio));
  }
} // namespace densify
