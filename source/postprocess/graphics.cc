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

#include <densify/postprocess/graphics.h>
#include <densify/postprocess/material_points.h>
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
    const std::vector<ParticleMeasure>                 *measures,
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

    // the material points as the assembly sees them
    MaterialPoints                       points(dof_handler,
                          mapping,
                          degree,
                          solution,
                          materials,
                          history,
                          history_per_cell,
                          nodal_averaging);
    const Quadrature<3>                 &quadrature = points.quadrature();
    FEValues<3>                          post_values(mapping,
                            post_fe,
                            quadrature,
                            update_values | update_JxW_values);
    std::vector<types::global_dof_index> post_dofs(post_fe.n_dofs_per_cell());
    Vector<double> cell_w(post_dofs.size()), cell_m(post_dofs.size()),
      cell_p(post_dofs.size()), cell_e(post_dofs.size());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const typename DoFHandler<3>::active_cell_iterator post_cell(
            &triangulation, cell->level(), cell->index(), &post_dof_handler);
          post_values.reinit(post_cell);
          const std::vector<MaterialPointValues> &values = points.reinit(cell);
          cell_w                                         = 0;
          cell_m                                         = 0;
          cell_p                                         = 0;
          cell_e                                         = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            for (unsigned int i = 0; i < post_dofs.size(); ++i)
              {
                const double v =
                  post_values.shape_value(i, q) * post_values.JxW(q);
                cell_w(i) += v * values[q].von_mises;
                cell_m(i) += v;
                cell_p(i) += v * (-trace(values[q].sigma) / 3.);
                cell_e(i) += v * values[q].plastic_strain;
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

    const unsigned int n_cells = triangulation.n_active_cells();
    Vector<float> particle_id(n_cells), rank(n_cells), mean_pressure(n_cells),
      mean_von_mises(n_cells);
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const unsigned int c = cell->active_cell_index();
        particle_id(c)       = cell->material_id();
        rank(c)              = cell->subdomain_id();
        if (measures != nullptr)
          {
            const ParticleMeasure &m = (*measures)[cell->material_id()];
            mean_pressure(c)         = -trace(m.mean_stress) / 3.;
            mean_von_mises(c)        = m.mean_von_mises;
          }
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
    if (measures != nullptr)
      {
        data_out.add_data_vector(mean_pressure, "particle_mean_pressure");
        data_out.add_data_vector(mean_von_mises, "particle_mean_von_mises");
      }
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
