// Graphics of the load steps: P1 projections of the material fields, the
// contact fields and the .pvtu/.pvd files.
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/vector.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/data_out.h>

#include <densify/assembly/nodal_averaging.h>
#include <densify/postprocess/graphics.h>
#include <densify/utilities.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace densify
{
  namespace
  {
    /// The symmetric four-point rule of a tetrahedron (exact for quadratics):
    /// point k lies nearest corner k and carries a quarter of the volume, as
    /// the corners of the nodal-averaged F-bar do in the residual.
    Quadrature<3>
    corner_quadrature()
    {
      const double a = (5. + 3. * std::sqrt(5.)) / 20.;
      const double b = (5. - std::sqrt(5.)) / 20.;
      return Quadrature<3>(std::vector<Point<3>>{Point<3>(b, b, b),
                                                 Point<3>(a, b, b),
                                                 Point<3>(b, a, b),
                                                 Point<3>(b, b, a)},
                           std::vector<double>(4, 1. / 24.));
    }



    /// Von Mises stress of the Cauchy stress belonging to P and F (MPa).
    double
    von_mises(const Tensor<2, 3> &P, const Tensor<2, 3> &F)
    {
      const Tensor<2, 3> sigma = P * transpose(F) / determinant(F);
      const Tensor<2, 3> s =
        sigma - trace(sigma) / 3. * unit_symmetric_tensor<3>();
      return std::sqrt(1.5 * scalar_product(s, s));
    }
  } // namespace



  void
  GraphicsWriter::write(
    const unsigned int                                  step,
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
    const std::string                                  &directory,
    const MPI_Comm                                      comm)
  {
    // scalar P1 fields: lumped L2 projections and nodal gaps
    const FE_SimplexP<3>    post_fe(1);
    const Triangulation<3> &triangulation = dof_handler.get_triangulation();
    DoFHandler<3>           post_dof_handler(triangulation);
    post_dof_handler.distribute_dofs(post_fe);
    const IndexSet post_owned = post_dof_handler.locally_owned_dofs();
    IndexSet       post_relevant;
    DoFTools::extract_locally_relevant_dofs(post_dof_handler, post_relevant);
    TrilinosWrappers::MPI::Vector pr_w(post_owned, comm),
      ep_w(post_owned, comm);
    TrilinosWrappers::MPI::Vector vm_w(post_owned, comm),
      vm_m(post_owned, comm), gap(post_owned, comm);
    SurfaceFieldSums surface;
    for (auto *v :
         {&surface.pressure, &surface.slip, &surface.status, &surface.weights})
      v->reinit(post_owned, comm);

    // With the nodal-averaged F-bar, Fbar and the history live at a cell's
    // four corners, which carry V/4 each in the residual: one point nearest
    // each corner with that weight. (deal.II 9.4's QGaussSimplex<3>(2) has
    // six points of unequal weight; their nearest corners carried 0.90 to
    // 1.07 times V/4, which biased the projected fields: the pressure
    // integral of tests/cli/plastic_field.sh by -4.7 %.) Otherwise the
    // history is per point of the assembly's rule.
    const Quadrature<3> quadrature =
      nodal_averaging ? corner_quadrature() :
                        Quadrature<3>(QGaussSimplex<3>(degree + 1));
    FEValues<3>                          fe_values(mapping,
                          dof_handler.get_fe(),
                          quadrature,
                          update_gradients | update_JxW_values);
    FEValues<3>                          post_values(mapping,
                            post_fe,
                            quadrature,
                            update_values | update_JxW_values);
    const FEValuesExtractors::Vector     u(0);
    std::vector<Tensor<2, 3>>            grad_u(quadrature.size());
    std::vector<types::global_dof_index> post_dofs(post_fe.n_dofs_per_cell());
    Vector<double> cell_w(post_dofs.size()), cell_m(post_dofs.size()),
      cell_p(post_dofs.size()), cell_e(post_dofs.size());
    Tensor<2, 3> P;
    Tensor<4, 3> A;
    // the reference-cell corner of largest barycentric weight at each point
    std::vector<unsigned int> nearest_corner(quadrature.size());
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      {
        const Point<3>             &x = quadrature.point(q);
        const std::array<double, 4> weight{
          {1. - x[0] - x[1] - x[2], x[0], x[1], x[2]}};
        nearest_corner[q] =
          std::max_element(weight.begin(), weight.end()) - weight.begin();
      }
    const std::vector<double> j_bar =
      nodal_averaging ?
        nodal_averaging->vertex_volume_measures(solution, materials) :
        std::vector<double>();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const typename DoFHandler<3>::active_cell_iterator post_cell(
            &triangulation, cell->level(), cell->index(), &post_dof_handler);
          fe_values.reinit(cell);
          post_values.reinit(post_cell);
          fe_values[u].get_function_gradients(solution, grad_u);
          cell_w = 0;
          cell_m = 0;
          cell_p = 0;
          cell_e = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad_u[q];
              // with the nodal-averaged F-bar the history is kept at the
              // corners: take the corner nearest to the point, and the
              // material's Fbar there (F alone would give the cell's own,
              // locking volume change to the pressure)
              const Material &material = *materials[cell->material_id()];
              if (nodal_averaging)
                {
                  const bool   finite = material.finite_strain();
                  const double j_a    = blended_volume_measure(
                    j_bar[cell->vertex_index(nearest_corner[q])],
                    finite ? determinant(F) : trace(F) - 2.,
                    nodal_averaging->cell_volume_weight(cell->material_id()),
                    finite);
                  F = fbar_deformation(F, j_a, finite);
                }
              const unsigned int k =
                cell->active_cell_index() * history_per_cell +
                (nodal_averaging ? nearest_corner[q] : q);
              MaterialState scratch;
              material.evaluate(F,
                                history != nullptr ? &(*history)[k] : nullptr,
                                history != nullptr ? &scratch : nullptr,
                                P,
                                A);
              const double       vm    = von_mises(P, F);
              const Tensor<2, 3> sigma = P * transpose(F) / determinant(F);
              const double       eps_p =
                history != nullptr ?
                        material.equivalent_plastic_strain((*history)[k]) :
                        0.;
              for (unsigned int i = 0; i < post_dofs.size(); ++i)
                {
                  const double v =
                    post_values.shape_value(i, q) * post_values.JxW(q);
                  cell_w(i) += v * vm;
                  cell_m(i) += v;
                  cell_p(i) += v * (-trace(sigma) / 3.);
                  cell_e(i) += v * eps_p;
                }
            }
          post_cell->get_dof_indices(post_dofs);
          vm_w.add(post_dofs, cell_w);
          vm_m.add(post_dofs, cell_m);
          pr_w.add(post_dofs, cell_p);
          ep_w.add(post_dofs, cell_e);
          // signed gap to the nearest tool at each vertex
          for (const unsigned int v : cell->vertex_indices())
            {
              const types::global_dof_index i =
                post_cell->vertex_dof_index(v, 0);
              if (!post_owned.is_element(i))
                continue;
              Point<3> x = cell->vertex(v);
              for (unsigned int d = 0; d < 3; ++d)
                x[d] += solution(cell->vertex_dof_index(v, d));
              double g = std::numeric_limits<double>::max();
              if (tool_contact != nullptr)
                for (const RigidTool &tool : tool_contact->tools())
                  {
                    Tensor<1, 3> n;
                    double       c;
                    g = std::min(g, tool.gap(x, n, c));
                  }
              gap(i) = (tool_contact != nullptr ? g : 0.);
            }
        }
    if (tool_contact != nullptr)
      tool_contact->project_fields(mapping,
                                   solution,
                                   post_dof_handler,
                                   surface);
    if (particle_contact != nullptr)
      particle_contact->project_fields(mapping,
                                       solution,
                                       post_dof_handler,
                                       surface);
    for (auto *v : {&vm_w,
                    &vm_m,
                    &surface.pressure,
                    &surface.slip,
                    &surface.status,
                    &surface.weights,
                    &pr_w,
                    &ep_w})
      v->compress(VectorOperation::add);
    gap.compress(VectorOperation::insert);
    for (const auto i : post_owned)
      {
        pr_w(i)        = (vm_m(i) > 0 ? pr_w(i) / vm_m(i) : 0.);
        ep_w(i)        = (vm_m(i) > 0 ? ep_w(i) / vm_m(i) : 0.);
        vm_w(i)        = (vm_m(i) > 0 ? vm_w(i) / vm_m(i) : 0.);
        const double w = surface.weights(i);
        for (auto *v : {&surface.pressure, &surface.slip, &surface.status})
          (*v)(i) = (w > 0 ? (*v)(i) / w : 0.);
      }
    vm_w.compress(VectorOperation::insert);
    for (auto *v : {&surface.pressure, &surface.slip, &surface.status})
      v->compress(VectorOperation::insert);
    pr_w.compress(VectorOperation::insert);
    ep_w.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector vm_g(post_owned, post_relevant, comm),
      p_g(post_owned, post_relevant, comm),
      gap_g(post_owned, post_relevant, comm),
      pr_g(post_owned, post_relevant, comm),
      ep_g(post_owned, post_relevant, comm),
      slip_g(post_owned, post_relevant, comm),
      status_g(post_owned, post_relevant, comm);
    vm_g     = vm_w;
    p_g      = surface.pressure;
    slip_g   = surface.slip;
    status_g = surface.status;
    gap_g    = gap;
    pr_g     = pr_w;
    ep_g     = ep_w;

    Vector<float> particle_id(triangulation.n_active_cells()),
      rank(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        particle_id(cell->active_cell_index()) = cell->material_id();
        rank(cell->active_cell_index())        = cell->subdomain_id();
      }

    DataOut<3> data_out;
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(
      solution,
      std::vector<std::string>(3, "displacement"),
      DataOut<3>::type_dof_data,
      std::vector<DataComponentInterpretation::DataComponentInterpretation>(
        3, DataComponentInterpretation::component_is_part_of_vector));
    data_out.add_data_vector(post_dof_handler, vm_g, "von_mises");
    data_out.add_data_vector(post_dof_handler, p_g, "contact_pressure");
    data_out.add_data_vector(post_dof_handler, gap_g, "gap");
    data_out.add_data_vector(post_dof_handler, pr_g, "pressure");
    if (friction)
      {
        data_out.add_data_vector(post_dof_handler, slip_g, "slip");
        data_out.add_data_vector(post_dof_handler, status_g, "stick_slip");
      }
    if (history != nullptr)
      data_out.add_data_vector(post_dof_handler, ep_g, "plastic_strain");
    data_out.add_data_vector(particle_id, "particle_id");
    data_out.add_data_vector(rank, "mpi_rank");
    data_out.build_patches(mapping, degree);
    const std::string dir = directory + "/";
    // a rank that cannot write (e.g. a full disk) stops every rank with the
    // file and the cause
    std::string pvtu, error;
    errno = 0;
    try
      {
        pvtu =
          data_out.write_vtu_with_pvtu_record(dir, "solution", step, comm, 5);
      }
    catch (const std::exception &)
      {
        error =
          "graphics: " + write_error(dir + "solution_" +
                                     Utilities::int_to_string(step, 5) + ".*");
      }
    error = first_error(error, comm);
    if (!error.empty())
      throw std::runtime_error(error);
    pvd_records.emplace_back(time, pvtu);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        // write then rename, so that the .pvd is always complete
        const std::string tmp = dir + "solution.pvd.tmp";
        errno                 = 0;
        std::ofstream pvd(tmp);
        DataOutBase::write_pvd_record(pvd, pvd_records);
        pvd.close();
        if (pvd.fail())
          {
            error = "graphics: " + write_error(tmp);
            std::error_code ignored;
            std::filesystem::remove(tmp, ignored);
          }
        else
          std::filesystem::rename(tmp, dir + "solution.pvd");
      }
    error = first_error(error, comm);
    if (!error.empty())
      throw std::runtime_error(error);
  }
} // namespace densify
