// The compact's current envelope and the particles' surface area.
#include <deal.II/base/mpi.h>

#include <densify/postprocess/compact_envelope.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace densify
{
  CompactEnvelope
  compact_envelope(const DoFHandler<3>                 &dof_handler,
                   const TrilinosWrappers::MPI::Vector &solution)
  {
    double bottom = std::numeric_limits<double>::max();
    double top = -std::numeric_limits<double>::max(), radius2 = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            Point<3> x = cell->vertex(v);
            for (unsigned int c = 0; c < 3; ++c)
              x[c] += solution(cell->vertex_dof_index(v, c));
            bottom  = std::min(bottom, x[2]);
            top     = std::max(top, x[2]);
            radius2 = std::max(radius2, x[0] * x[0] + x[1] * x[1]);
          }
    const MPI_Comm  comm = dof_handler.get_communicator();
    CompactEnvelope envelope;
    envelope.bottom = Utilities::MPI::min(bottom, comm);
    envelope.top    = Utilities::MPI::max(top, comm);
    envelope.radius = std::sqrt(Utilities::MPI::max(radius2, comm));
    return envelope;
  }



  double
  particle_surface_area(const DoFHandler<3>                 &dof_handler,
                        const TrilinosWrappers::MPI::Vector &solution)
  {
    double area = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto              face = cell->face(f);
              std::array<Point<3>, 3> x;
              for (unsigned int a = 0; a < 3; ++a)
                {
                  x[a] = face->vertex(a);
                  for (unsigned int c = 0; c < 3; ++c)
                    x[a][c] += solution(face->vertex_dof_index(a, c));
                }
              area += 0.5 * cross_product_3d(x[1] - x[0], x[2] - x[0]).norm();
            }
    return Utilities::MPI::sum(area, dof_handler.get_communicator());
  }
} // namespace densify
