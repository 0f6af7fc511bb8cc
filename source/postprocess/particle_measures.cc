// Measures of each particle, its mean stress, and the particles.csv writer.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <densify/assembly/all_values.h>
#include <densify/postprocess/particle_measures.h>
#include <densify/utilities.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace densify
{
  std::vector<ParticleMeasure>
  measure_particles(
    const DoFHandler<3>                                &dof_handler,
    const Mapping<3>                                   &mapping,
    const unsigned int                                  degree,
    const TrilinosWrappers::MPI::Vector                &solution,
    const std::vector<Particle>                        &particles,
    const std::vector<std::shared_ptr<const Material>> &materials,
    const MPI_Comm                                      comm)
  {
    // per particle, with r = X - centre: [0] current volume, [1] reference
    // volume, [2..4] int u, [5..7] int r x u, [8..10] int r, [11..19] the
    // inertia tensor int (|r|^2 I - r r)
    constexpr unsigned int n = 20;
    std::vector<double>    sums(n * particles.size(), 0.);
    // adds to particle p's sums a point of weight JxW with the volume
    // measure, r and u there, and the integrals of r (x) u and r (x) r over
    // the point's share
    const auto add = [&](const unsigned int  p,
                         const double        volume_measure,
                         const double        JxW,
                         const Tensor<1, 3> &r,
                         const Tensor<1, 3> &u_at_point,
                         const Tensor<2, 3> &r_u,
                         const Tensor<2, 3> &r_r) {
      double      *sum = &sums[n * p];
      Tensor<1, 3> r_x_u;
      r_x_u[0] = r_u[1][2] - r_u[2][1];
      r_x_u[1] = r_u[2][0] - r_u[0][2];
      r_x_u[2] = r_u[0][1] - r_u[1][0];
      sum[0] += volume_measure * JxW;
      sum[1] += JxW;
      for (unsigned int d = 0; d < 3; ++d)
        {
          sum[2 + d] += u_at_point[d] * JxW;
          sum[5 + d] += r_x_u[d];
          sum[8 + d] += r[d] * JxW;
          for (unsigned int e = 0; e < 3; ++e)
            sum[11 + 3 * d + e] += (d == e ? trace(r_r) : 0.) - r_r[d][e];
        }
    };
    if (degree == 1)
      {
        // linear tetrahedra: u and r are linear in the cell, so the
        // integrals of the quadratic integrands have closed forms in the
        // vertex values, int f g = V/20 (sum_v f_v g_v + sum_v f_v sum_v
        // g_v) and int f = V/4 sum_v f_v, the values of a rule exact for
        // quadratics, without a mapping
        AllValues values;
        values.gather(solution);
        const FiniteElement<3>              &fe = dof_handler.get_fe();
        std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dofs);
              const unsigned int          p = cell->material_id();
              std::array<Tensor<1, 3>, 4> r, u_v;
              for (unsigned int v = 0; v < 4; ++v)
                r[v] = cell->vertex(v) - particles[p].centre;
              for (unsigned int i = 0; i < dofs.size(); ++i)
                {
                  const auto [component, vertex] =
                    fe.system_to_component_index(i);
                  u_v[vertex][component] = values[dofs[i]];
                }
              // F from the vertex values: Grad u = [u1 - u0, u2 - u0,
              // u3 - u0] [X1 - X0, X2 - X0, X3 - X0]^-1
              Tensor<2, 3> dX, dU;
              for (unsigned int v = 1; v < 4; ++v)
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    dX[d][v - 1] = r[v][d] - r[0][d];
                    dU[d][v - 1] = u_v[v][d] - u_v[0][d];
                  }
              const double       V      = std::abs(determinant(dX)) / 6.;
              const Tensor<2, 3> grad_u = dU * invert(dX);
              const bool         finite = materials[p]->finite_strain();
              const double       measure =
                finite ? determinant(unit_symmetric_tensor<3>() + grad_u) :
                               1. + trace(grad_u);
              Tensor<1, 3> r_sum, u_sum;
              Tensor<2, 3> r_u, r_r;
              for (unsigned int v = 0; v < 4; ++v)
                {
                  r_sum += r[v];
                  u_sum += u_v[v];
                  r_u += outer_product(r[v], u_v[v]);
                  r_r += outer_product(r[v], r[v]);
                }
              r_u = V / 20. * (r_u + outer_product(r_sum, u_sum));
              r_r = V / 20. * (r_r + outer_product(r_sum, r_sum));
              // the means of r and u carry the whole volume
              add(p, measure, V, r_sum / 4., u_sum / 4., r_u, r_r);
            }
      }
    else
      {
        const QGaussSimplex<3>           quadrature(degree + 1);
        FEValues<3>                      fe_values(mapping,
                              dof_handler.get_fe(),
                              quadrature,
                              update_values | update_gradients |
                                update_quadrature_points | update_JxW_values);
        const FEValuesExtractors::Vector u(0);
        std::vector<Tensor<1, 3>>        u_q(quadrature.size());
        std::vector<Tensor<2, 3>>        grad_u(quadrature.size());
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              fe_values[u].get_function_values(solution, u_q);
              fe_values[u].get_function_gradients(solution, grad_u);
              const unsigned int p      = cell->material_id();
              const bool         finite = materials[p]->finite_strain();
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                {
                  const double JxW = fe_values.JxW(q);
                  // volume as the kinematics of the particle's law sees it
                  // (det F is not rotation-free for linearised rotations)
                  const double measure =
                    finite ?
                      determinant(unit_symmetric_tensor<3>() + grad_u[q]) :
                      1. + trace(grad_u[q]);
                  const Tensor<1, 3> r =
                    fe_values.quadrature_point(q) - particles[p].centre;
                  add(p,
                      measure,
                      JxW,
                      r,
                      u_q[q],
                      JxW * outer_product(r, u_q[q]),
                      JxW * outer_product(r, r));
                }
            }
      }
    Utilities::MPI::sum(sums, comm, sums);
    std::vector<ParticleMeasure> measures(particles.size());
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        const double *sum  = &sums[n * p];
        measures[p].volume = sum[0];
        Tensor<1, 3> mean, moment, first;
        Tensor<2, 3> inertia;
        for (unsigned int d = 0; d < 3; ++d)
          {
            mean[d]   = sum[2 + d] / sum[1];
            moment[d] = sum[5 + d];
            first[d]  = sum[8 + d];
            for (unsigned int e = 0; e < 3; ++e)
              inertia[d][e] = sum[11 + 3 * d + e];
          }
        measures[p].mean_displacement = mean;
        // rigid rotation u = w x r gives int r x u = I w; the translation
        // part is taken out first
        measures[p].rotation =
          invert(inertia) * (moment - cross_product_3d(first, mean));
      }
    return measures;
  }



  void
  measure_particle_stresses(const DoFHandler<3>          &dof_handler,
                            MaterialPoints               &points,
                            std::vector<ParticleMeasure> &measures,
                            const MPI_Comm                comm)
  {
    // per particle: [0] current volume, [1] int von Mises, [2..10] int sigma
    constexpr unsigned int n = 11;
    std::vector<double>    sums(n * measures.size(), 0.);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          double *sum = &sums[n * cell->material_id()];
          for (const MaterialPointValues &v : points.reinit(cell))
            {
              const double dv = v.volume_ratio * v.JxW;
              sum[0] += dv;
              sum[1] += v.von_mises * dv;
              for (unsigned int d = 0; d < 3; ++d)
                for (unsigned int e = 0; e < 3; ++e)
                  sum[2 + 3 * d + e] += v.sigma[d][e] * dv;
            }
        }
    Utilities::MPI::sum(sums, comm, sums);
    for (unsigned int p = 0; p < measures.size(); ++p)
      {
        const double *sum = &sums[n * p];
        if (!(sum[0] > 0.))
          continue;
        measures[p].mean_von_mises = sum[1] / sum[0];
        for (unsigned int d = 0; d < 3; ++d)
          for (unsigned int e = 0; e < 3; ++e)
            measures[p].mean_stress[d][e] = sum[2 + 3 * d + e] / sum[0];
      }
  }



  ParticleTableWriter::ParticleTableWriter(const std::string &filename,
                                           const bool         append)
    : filename(filename)
  {
    if (append)
      extend_csv_columns(filename, header());
    out.open(filename, append ? std::ios::app : std::ios::trunc);
    if (!append)
      {
        const std::string error =
          append_or_roll_back(out, filename, header() + "\n");
        if (!error.empty())
          throw std::runtime_error(error);
      }
  }



  std::string
  ParticleTableWriter::header()
  {
    return "step,particle,material,volume,initial_volume,"
           "mean_displacement_x,mean_displacement_y,"
           "mean_displacement_z,rotation_x,rotation_y,"
           "rotation_z,contact_partners,die_contact,mean_pressure,"
           "mean_von_mises,mean_stress_xx,mean_stress_yy,mean_stress_zz,"
           "mean_stress_xy,mean_stress_yz,mean_stress_xz";
  }



  std::string
  ParticleTableWriter::write(const unsigned int                  step,
                             const std::vector<Particle>        &particles,
                             const std::vector<ParticleMeasure> &measures,
                             const std::vector<double>       &initial_volumes,
                             const std::vector<unsigned int> &partners,
                             const std::vector<double>       &die_force)
  {
    std::ostringstream rows;
    for (unsigned int p = 0; p < particles.size(); ++p)
      {
        const Tensor<2, 3> &stress = measures[p].mean_stress;
        rows << step << ',' << p << ',' << particles[p].material << ','
             << std::setprecision(10) << measures[p].volume << ','
             << initial_volumes[p] << ',' << measures[p].mean_displacement[0]
             << ',' << measures[p].mean_displacement[1] << ','
             << measures[p].mean_displacement[2] << ','
             << measures[p].rotation[0] << ',' << measures[p].rotation[1] << ','
             << measures[p].rotation[2] << ',' << partners[p] << ','
             << (die_force[p] > 0 ? 1 : 0) << ','
             << -trace(measures[p].mean_stress) / 3. << ','
             << measures[p].mean_von_mises << ',' << stress[0][0] << ','
             << stress[1][1] << ',' << stress[2][2] << ',' << stress[0][1]
             << ',' << stress[1][2] << ',' << stress[0][2] << '\n';
      }
    return append_or_roll_back(out, filename, rows.str());
  }
} // namespace densify
