// Augmented-Lagrangian normal contact between particle surfaces and the rigid
// tools.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/fe/fe_values.h>

#include <densify/contact/tool_contact.h>

namespace densify
{
  void
  ToolContact::setup(const DoFHandler<3>          &dof_handler,
                     const std::vector<RigidTool> &tools,
                     const std::vector<double>    &penalty_per_particle,
                     const unsigned int            quadrature_points_1d)
  {
    this->dof_handler = &dof_handler;
    tool_list         = tools;
    penalty           = penalty_per_particle;
    face_quadrature   = QGaussSimplex<2>(quadrature_points_1d);
    faces.clear();
    if (!tool_list.empty())
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              faces.emplace_back(cell, f);
    lambda.assign(faces.size() * face_quadrature.size() * tool_list.size(), 0.);
  }



  void
  ToolContact::set_tool_position(const ToolKind kind, const double position)
  {
    for (RigidTool &tool : tool_list)
      if (tool.kind == kind)
        tool.position = position;
  }



  ToolContactResult
  ToolContact::loop(const Mapping<3>                    &mapping,
                    const TrilinosWrappers::MPI::Vector &solution,
                    TrilinosWrappers::MPI::Vector       *residual,
                    TrilinosWrappers::SparseMatrix      *matrix,
                    const double                         tangent_margin,
                    std::vector<double>                 *new_lambda,
                    const DoFHandler<3>                 *post_dof_handler,
                    TrilinosWrappers::MPI::Vector       *weighted,
                    TrilinosWrappers::MPI::Vector       *weights) const
  {
    ToolContactResult result;
    if (faces.empty() && tool_list.empty())
      return result;

    const FiniteElement<3>          &fe      = dof_handler->get_fe();
    const unsigned int               n_q     = face_quadrature.size();
    const unsigned int               n_dofs  = fe.n_dofs_per_cell();
    const unsigned int               n_tools = tool_list.size();
    FEFaceValues<3>                  fe_face(mapping,
                            fe,
                            face_quadrature,
                            update_values | update_quadrature_points |
                              update_JxW_values);
    std::unique_ptr<FEFaceValues<3>> post_face;
    if (post_dof_handler != nullptr)
      post_face =
        std::make_unique<FEFaceValues<3>>(mapping,
                                          post_dof_handler->get_fe(),
                                          face_quadrature,
                                          update_values | update_JxW_values);

    const FEValuesExtractors::Vector     u(0);
    std::vector<Tensor<1, 3>>            u_values(n_q);
    std::vector<Tensor<1, 3>>            phi(n_dofs);
    std::vector<double>                  n_phi(n_dofs);
    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs);
    Vector<double>                       cell_residual(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    std::vector<types::global_dof_index> post_indices;
    Vector<double>                       post_weighted, post_weights;

    for (unsigned int k = 0; k < faces.size(); ++k)
      {
        const auto &[cell, f] = faces[k];
        fe_face.reinit(cell, f);
        fe_face[u].get_function_values(solution, u_values);
        const double eps     = penalty[cell->material_id()];
        bool         touched = false;
        cell_matrix          = 0;
        cell_residual        = 0;
        if (post_face)
          {
            const typename DoFHandler<3>::active_cell_iterator post_cell(
              &cell->get_triangulation(),
              cell->level(),
              cell->index(),
              post_dof_handler);
            post_face->reinit(post_cell, f);
            post_indices.resize(post_face->get_fe().n_dofs_per_cell());
            post_cell->get_dof_indices(post_indices);
            post_weighted.reinit(post_indices.size());
            post_weights.reinit(post_indices.size());
          }

        for (unsigned int q = 0; q < n_q; ++q)
          {
            const Point<3> x     = fe_face.quadrature_point(q) + u_values[q];
            const double   JxW   = fe_face.JxW(q);
            double         p_sum = 0;
            for (unsigned int t = 0; t < n_tools; ++t)
              {
                const RigidTool &tool = tool_list[t];
                Tensor<1, 3>     n;
                double           curvature;
                const double     g   = tool.gap(x, n, curvature);
                const unsigned   idx = (k * n_q + q) * n_tools + t;
                const double     p   = std::max(0., lambda[idx] - eps * g);
                if (new_lambda != nullptr)
                  (*new_lambda)[idx] = p;
                result.max_penetration = std::max(result.max_penetration, -g);
                const bool predicted =
                  (p <= 0. && matrix != nullptr && g < tangent_margin);
                if (p <= 0. && !predicted)
                  continue;
                if (predicted)
                  {
                    // near contact: stiffness in the tangent only (predictor)
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      n_phi[i] = n * fe_face[u].value(i, q);
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      for (unsigned int j = 0; j < n_dofs; ++j)
                        cell_matrix(i, j) += eps * n_phi[i] * n_phi[j] * JxW;
                    touched = true;
                    continue;
                  }
                p_sum += p;
                ++result.n_active;
                const unsigned int kind = static_cast<unsigned int>(tool.kind);
                result.normal_force[kind] += p * JxW;
                result.axial_force[kind] += -p * n[2] * JxW;
                if (residual == nullptr)
                  continue;
                touched = true;
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    phi[i]   = fe_face[u].value(i, q);
                    n_phi[i] = n * phi[i];
                    cell_residual(i) -= p * n_phi[i] * JxW;
                  }
                if (matrix == nullptr)
                  continue;
                for (unsigned int i = 0; i < n_dofs; ++i)
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += eps * n_phi[i] * n_phi[j] * JxW;
                if (curvature > 0)
                  // concave die wall: p d(n)/dx = p/r (I_h - e_r e_r), PSD
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      {
                        const double horizontal =
                          phi[i][0] * phi[j][0] + phi[i][1] * phi[j][1];
                        cell_matrix(i, j) +=
                          p * curvature * (horizontal - n_phi[i] * n_phi[j]) *
                          JxW;
                      }
              }
            if (post_face)
              for (unsigned int i = 0; i < post_indices.size(); ++i)
                {
                  const double v = post_face->shape_value(i, q) * JxW;
                  post_weighted(i) += v * p_sum;
                  post_weights(i) += v;
                }
          }
        if (post_face)
          {
            weighted->add(post_indices, post_weighted);
            weights->add(post_indices, post_weights);
          }
        if (touched)
          {
            cell->get_dof_indices(dof_indices);
            residual->add(dof_indices, cell_residual);
            if (matrix != nullptr)
              matrix->add(dof_indices, cell_matrix);
          }
      }

    const MPI_Comm comm = dof_handler->get_communicator();
    for (unsigned int t = 0; t < n_tool_kinds; ++t)
      {
        result.normal_force[t] =
          Utilities::MPI::sum(result.normal_force[t], comm);
        result.axial_force[t] =
          Utilities::MPI::sum(result.axial_force[t], comm);
      }
    result.max_penetration = Utilities::MPI::max(result.max_penetration, comm);
    result.n_active        = Utilities::MPI::sum(result.n_active, comm);
    return result;
  }



  ToolContactResult
  ToolContact::assemble(const Mapping<3>                    &mapping,
                        const TrilinosWrappers::MPI::Vector &solution,
                        TrilinosWrappers::MPI::Vector       &residual,
                        TrilinosWrappers::SparseMatrix      *matrix,
                        const double tangent_margin) const
  {
    return loop(mapping,
                solution,
                &residual,
                matrix,
                tangent_margin,
                nullptr,
                nullptr,
                nullptr,
                nullptr);
  }



  ToolContactResult
  ToolContact::evaluate(const Mapping<3>                    &mapping,
                        const TrilinosWrappers::MPI::Vector &solution) const
  {
    return loop(mapping,
                solution,
                nullptr,
                nullptr,
                0.,
                nullptr,
                nullptr,
                nullptr,
                nullptr);
  }



  void
  ToolContact::update_multipliers(const Mapping<3>                    &mapping,
                                  const TrilinosWrappers::MPI::Vector &solution)
  {
    std::vector<double> new_lambda(lambda.size());
    loop(mapping,
         solution,
         nullptr,
         nullptr,
         0.,
         &new_lambda,
         nullptr,
         nullptr,
         nullptr);
    lambda.swap(new_lambda);
  }



  void
  ToolContact::project_pressure(const Mapping<3>                    &mapping,
                                const TrilinosWrappers::MPI::Vector &solution,
                                const DoFHandler<3>           &post_dof_handler,
                                TrilinosWrappers::MPI::Vector &weighted,
                                TrilinosWrappers::MPI::Vector &weights) const
  {
    loop(mapping,
         solution,
         nullptr,
         nullptr,
         0.,
         nullptr,
         &post_dof_handler,
         &weighted,
         &weights);
  }
} // namespace densify
