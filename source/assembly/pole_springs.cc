// The pole springs (Contact/Hold poles on axis).
#include <deal.II/base/mpi.h>

#include <deal.II/lac/full_matrix.h>

#include <densify/assembly/pole_springs.h>

#include <cmath>
#include <stdexcept>

namespace densify
{
  PoleSprings::PoleSprings(const DoFHandler<3>         &dof_handler,
                           const std::vector<Particle> &particles,
                           const std::vector<double>   &stiffness,
                           const bool                   vertical,
                           const bool                   spin_springs)
    : comm(dof_handler.get_communicator())
  {
    const IndexSet &locally_owned = dof_handler.locally_owned_dofs();
    // the pole vertices' horizontal DoFs of each particle: [p][top?][d]. The
    // shared triangulation knows every cell, so every rank finds all of them
    constexpr types::global_dof_index none = numbers::invalid_dof_index;
    std::vector<std::array<std::array<types::global_dof_index, 2>, 2>> pole(
      particles.size(), {{{{none, none}}, {{none, none}}}});
    // the y DoF of the surface vertex farthest along +x from the centre: it
    // moves sideways when the particle spins about its vertical axis
    std::vector<types::global_dof_index> spin(particles.size(), none);
    std::vector<double>                  spin_x(particles.size(), 0.);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const unsigned int p = cell->material_id();
        const double       R = particles[p].diameter / 2;
        for (const unsigned int v : cell->vertex_indices())
          {
            const Tensor<1, 3> r = cell->vertex(v) - particles[p].centre;
            if (r[0] > spin_x[p])
              {
                spin_x[p] = r[0];
                spin[p]   = cell->vertex_dof_index(v, 1);
              }
            if (std::abs(std::abs(r[2]) - R) > 1e-8 * R ||
                r[0] * r[0] + r[1] * r[1] > 1e-16 * R * R)
              continue;
            for (unsigned int d = 0; d < 2; ++d)
              pole[p][r[2] > 0 ? 1 : 0][d] = cell->vertex_dof_index(v, d);
          }
      }
    unsigned int n_found = 0;
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        const double k = stiffness[p];
        for (unsigned int d = 0; d < 2; ++d)
          {
            const types::global_dof_index bottom = pole[p][0][d],
                                          top    = pole[p][1][d];
            n_found += (bottom != none) + (top != none);
            if (bottom == none || top == none)
              continue;
            if (vertical)
              {
                // one spring between the poles, added by the owner of one
                if (locally_owned.is_element(top))
                  springs.push_back({top, bottom, k});
              }
            else
              for (const types::global_dof_index i : {bottom, top})
                if (locally_owned.is_element(i))
                  springs.push_back({i, none, k});
          }
        // against the spin: between that vertex's y DoF and the top pole's.
        // Only for a vertical stack (axis with particle contact): flat
        // frictionless punches exert no torque about the axis, the facets of
        // another particle do. In a layer (vertical) the spring changed the
        // frictionless seven-sphere test's contact force by 12 % and let the
        // outer ring drift by 0.18 mm, which it does not do without it
        if (spin_springs && spin[p] != none && pole[p][1][1] != none &&
            locally_owned.is_element(spin[p]))
          springs.push_back({spin[p], pole[p][1][1], k});
      }
    if (n_found != 4 * particles.size())
      throw std::runtime_error(
        "Contact/Hold poles on axis: found " + std::to_string(n_found / 2) +
        " pole vertices for " + std::to_string(particles.size()) +
        " particle(s); the poles must be mesh vertices (they are for the "
        "gmsh spheres of Densify)");
  }



  void
  PoleSprings::add_couplings(TrilinosWrappers::SparsityPattern &pattern)
  {
    for (const Spring &s : springs)
      if (s.j != numbers::invalid_dof_index)
        {
          pattern.add(s.i, s.j);
          pattern.add(s.j, s.i);
          pattern.add(s.j, s.j);
        }
  }



  void
  PoleSprings::assemble(const AssemblyContext          &context,
                        TrilinosWrappers::MPI::Vector  &residual,
                        TrilinosWrappers::SparseMatrix *tangent)
  {
    const TrilinosWrappers::MPI::Vector &u      = *context.solution;
    double                               force2 = 0;
    for (const Spring &s : springs)
      if (s.j == numbers::invalid_dof_index)
        {
          // towards zero
          const double f = s.k * u(s.i);
          residual(s.i) += f;
          force2 += f * f;
          if (tangent != nullptr)
            tangent->add(s.i, s.i, s.k);
        }
      else
        {
          // between two poles (the bottom one may belong to another rank)
          const double f = s.k * (u(s.i) - u(s.j));
          const std::vector<types::global_dof_index> dofs = {s.i, s.j};
          residual.add(dofs, std::vector<double>{f, -f});
          force2 += f * f;
          if (tangent != nullptr)
            {
              FullMatrix<double> k(2, 2);
              k(0, 0) = k(1, 1) = s.k;
              k(0, 1) = k(1, 0) = -s.k;
              tangent->add(dofs, k);
            }
        }
    last_force = std::sqrt(Utilities::MPI::sum(force2, comm));
  }
} // namespace densify
