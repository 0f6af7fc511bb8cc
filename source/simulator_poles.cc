// Pole springs of the Simulator (Contact/Hold poles on axis): horizontal
// springs that hold the top and bottom pole vertex of every particle on the
// vertical line through its centre.
#include <deal.II/base/mpi.h>

#include <densify/simulator.h>

#include <cmath>

namespace densify
{
  void
  Simulator::setup_pole_springs()
  {
    pole_springs.clear();
    if (!prm.contact.hold_poles)
      return;
    // the stiffness of a penalty contact on an element face: penalty * h^2
    std::vector<bool> seen(dof_handler.n_dofs(), false);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int p = cell->material_id();
          const double       R = particles[p].diameter / 2;
          const double       k = prm.contact.penalty_factor *
                           particle_material[p]->youngs_modulus() * h_min;
          for (const unsigned int v : cell->vertex_indices())
            {
              const Tensor<1, 3> r = cell->vertex(v) - particles[p].centre;
              if (std::abs(std::abs(r[2]) - R) > 1e-8 * R ||
                  r[0] * r[0] + r[1] * r[1] > 1e-16 * R * R)
                continue;
              for (unsigned int d = 0; d < 2; ++d)
                {
                  const types::global_dof_index i =
                    cell->vertex_dof_index(v, d);
                  if (locally_owned.is_element(i) && !seen[i])
                    {
                      seen[i] = true;
                      pole_springs.emplace_back(i, k);
                    }
                }
            }
        }
    const unsigned int n =
      Utilities::MPI::sum(static_cast<unsigned int>(pole_springs.size()), comm);
    if (n != 4 * particles.size())
      throw std::runtime_error(
        "Contact/Hold poles on axis: found " + std::to_string(n / 2) +
        " pole vertices for " + std::to_string(particles.size()) +
        " particle(s); the poles must be mesh vertices (they are for the "
        "gmsh spheres of Densify)");
  }



  double
  Simulator::add_pole_springs(const bool with_matrix)
  {
    double force2 = 0;
    for (const auto &[i, k] : pole_springs)
      {
        const double f = k * solution(i);
        residual(i) += f;
        force2 += f * f;
        if (with_matrix)
          tangent.add(i, i, k);
      }
    return std::sqrt(Utilities::MPI::sum(force2, comm));
  }
} // namespace densify
