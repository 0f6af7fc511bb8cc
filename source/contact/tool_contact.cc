// Augmented-Lagrangian contact with Coulomb friction between particle
// surfaces and the rigid tools.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>

#include <deal.II/fe/fe_values.h>

#include <densify/contact/tool_contact.h>

#include <algorithm>
#include <memory>

namespace densify
{
  void
  add_surface_field_values(const std::vector<types::global_dof_index> &dofs,
                           const Vector<double>                       &p,
                           const Vector<double>                       &slip,
                           const Vector<double>                       &status,
                           const Vector<double>                       &weights,
                           SurfaceFieldSums                           &sums)
  {
    sums.pressure.add(dofs, p);
    sums.slip.add(dofs, slip);
    sums.status.add(dofs, status);
    sums.weights.add(dofs, weights);
  }



  void
  ToolContact::setup(const DoFHandler<3>            &dof_handler,
                     const std::vector<RigidTool>   &tools,
                     const std::vector<FrictionLaw> &friction,
                     const std::vector<double>      &penalty_per_particle,
                     const Quadrature<2>            &contact_quadrature)
  {
    this->dof_handler = &dof_handler;
    tool_list         = tools;
    friction_laws     = friction;
    penalty           = penalty_per_particle;
    face_quadrature   = contact_quadrature;
    tables            = FaceTables();
    vertices          = Vertices();
    shift.assign(tools.size(), Tensor<1, 3>());
    committed_shift = shift;
    faces.clear();
    if (!tool_list.empty())
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              faces.emplace_back(cell, f);
    const std::size_t n_points =
      faces.size() * face_quadrature.size() * tool_list.size();
    lambda.assign(n_points, 0.);
    // friction history only if some tool has friction
    bool friction_on = false;
    for (const FrictionLaw &law : friction_laws)
      friction_on = friction_on || law.mu > 0;
    committed_traction.assign(friction_on ? n_points : 0, Tensor<1, 3>());
    accumulated_slip.assign(friction_on ? n_points : 0, 0.);
  }



  void
  ToolContact::set_tool_position(const ToolKind kind, const double position)
  {
    for (RigidTool &tool : tool_list)
      if (tool.kind == kind)
        tool.position = position;
  }



  void
  ToolContact::set_tool_top(const ToolKind kind, const double top)
  {
    for (RigidTool &tool : tool_list)
      if (tool.kind == kind)
        tool.top = top;
  }



  void
  ToolContact::set_tool_translation(const ToolKind      kind,
                                    const Tensor<1, 3> &translation)
  {
    for (unsigned int t = 0; t < tool_list.size(); ++t)
      if (tool_list[t].kind == kind)
        shift[t] = translation;
  }



  ToolContactResult
  ToolContact::loop(const Mapping<3>                    &mapping,
                    const TrilinosWrappers::MPI::Vector &solution,
                    const Outputs                       &out) const
  {
    ToolContactResult result;
    if (faces.empty() && tool_list.empty())
      return result;

    const bool friction_on = has_friction();
    Assert(!friction_on || committed_solution != nullptr,
           ExcMessage("friction needs set_committed_solution()"));
    const FiniteElement<3>          &fe      = dof_handler->get_fe();
    const unsigned int               n_q     = face_quadrature.size();
    const unsigned int               n_dofs  = fe.n_dofs_per_cell();
    const unsigned int               n_tools = tool_list.size();
    std::unique_ptr<FEFaceValues<3>> post_face;
    if (out.post != nullptr)
      post_face =
        std::make_unique<FEFaceValues<3>>(mapping,
                                          out.post->get_fe(),
                                          face_quadrature,
                                          update_values | update_JxW_values);

    const FEValuesExtractors::Vector     u(0);
    std::vector<Tensor<1, 3>>            u_values(n_q), u_old(n_q);
    std::vector<Tensor<1, 3>>            phi(n_dofs);
    std::vector<Tensor<1, 3>>            D_phi(n_dofs);
    FullMatrix<double>                   cell_matrix(n_dofs, n_dofs);
    Vector<double>                       cell_residual(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    std::vector<types::global_dof_index> post_indices;
    Vector<double> post_p, post_slip, post_status, post_weights;
    // explicit dynamics: plain arrays in and out, the faces' data made once
    const bool plain = out.values != nullptr && out.plain_residual != nullptr;
    std::unique_ptr<FEFaceValues<3>> fe_face;
    if (!plain)
      fe_face = std::make_unique<FEFaceValues<3>>(mapping,
                                                  fe,
                                                  face_quadrature,
                                                  update_values |
                                                    update_quadrature_points |
                                                    update_JxW_values);
    if (plain && !tables.ready())
      {
        tables.reinit(mapping, fe, face_quadrature, faces);
        face_vertices.resize(3 * faces.size());
        face_vertex_dofs.resize(9 * faces.size());
        for (unsigned int k = 0; k < faces.size(); ++k)
          for (unsigned int v = 0; v < 3; ++v)
            {
              const auto face          = faces[k].first->face(faces[k].second);
              face_vertices[3 * k + v] = face->vertex(v);
              for (unsigned int d = 0; d < 3; ++d)
                face_vertex_dofs[9 * k + 3 * v + d] =
                  face->vertex_dof_index(v, d);
            }
      }

    // A face of linear elements stays flat, so a tool's gap at its points
    // is at least the smallest gap at its vertices (a plane's gap is linear
    // on it, the die wall's concave). A face whose vertices are all further
    // from every tool than the gap at which a point could carry pressure
    // (lambda / eps) or enter the tangent as predicted has no point in
    // contact: it is skipped, with the open points' outputs written, unless
    // surface fields are asked for (in a late step of the paper scene most
    // faces are far from every tool).
    const bool   may_skip = fe.degree == 1 && out.post == nullptr;
    const double margin =
      out.matrix != nullptr ? std::max(out.tangent_margin, 0.) : 0.;
    const auto far_from_tools = [&](const unsigned int k) {
      const auto &[cell, f] = faces[k];
      const auto   face     = cell->face(f);
      const double eps      = penalty[cell->material_id()];
      Point<3>     x[3];
      for (unsigned int v = 0; v < 3; ++v)
        if (plain)
          {
            x[v] = face_vertices[3 * k + v];
            for (unsigned int d = 0; d < 3; ++d)
              x[v][d] += (*out.values)[face_vertex_dofs[9 * k + 3 * v + d]];
          }
        else
          {
            x[v] = face->vertex(v);
            for (unsigned int d = 0; d < 3; ++d)
              x[v][d] += solution(face->vertex_dof_index(v, d));
          }
      for (unsigned int t = 0; t < n_tools; ++t)
        {
          double lambda_max = 0.;
          for (unsigned int q = 0; q < n_q; ++q)
            lambda_max =
              std::max(lambda_max, lambda[(k * n_q + q) * n_tools + t]);
          const double needed = std::max(margin, lambda_max / eps);
          Tensor<1, 3> n;
          double       curvature;
          for (unsigned int v = 0; v < 3; ++v)
            if (!(tool_list[t].gap(x[v], n, curvature) > needed))
              return false;
        }
      return true;
    };

    // linear elements with their corners as contact points: each surface
    // vertex once (the explicit pass)
    const bool by_vertex = plain && out.post == nullptr &&
                           out.matrix == nullptr && vertex_evaluation &&
                           vertex_pass(out, result);
    for (unsigned int k = 0; !by_vertex && k < faces.size(); ++k)
      {
        const auto &[cell, f] = faces[k];
        if (may_skip && far_from_tools(k))
          {
            for (unsigned int q = 0; q < n_q; ++q)
              for (unsigned int t = 0; t < n_tools; ++t)
                {
                  const unsigned int idx = (k * n_q + q) * n_tools + t;
                  if (out.new_lambda != nullptr)
                    (*out.new_lambda)[idx] = 0.;
                  if (out.new_traction != nullptr && friction_on &&
                      friction_laws[t].mu > 0.)
                    (*out.new_traction)[idx] = Tensor<1, 3>();
                }
            continue;
          }
        if (plain)
          {
            tables.values(k, *out.values, u_values);
            if (friction_on)
              tables.values(k, *out.committed_values, u_old);
          }
        else
          {
            fe_face->reinit(cell, f);
            (*fe_face)[u].get_function_values(solution, u_values);
            if (friction_on)
              (*fe_face)[u].get_function_values(*committed_solution, u_old);
          }
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
              out.post);
            post_face->reinit(post_cell, f);
            const unsigned int n_post = post_face->get_fe().n_dofs_per_cell();
            post_indices.resize(n_post);
            post_cell->get_dof_indices(post_indices);
            for (auto *v : {&post_p, &post_slip, &post_status, &post_weights})
              v->reinit(n_post);
          }

        for (unsigned int q = 0; q < n_q; ++q)
          {
            const Point<3> x =
              (plain ? tables.point(k, q) : fe_face->quadrature_point(q)) +
              u_values[q];
            const double JxW   = plain ? tables.JxW(k, q) : fe_face->JxW(q);
            double       p_sum = 0, slip_sum = 0, status_max = 0;
            bool         have_phi = false;
            for (unsigned int t = 0; t < n_tools; ++t)
              {
                const RigidTool &tool = tool_list[t];
                Tensor<1, 3>     n;
                double           curvature;
                const double     g   = tool.gap(x, n, curvature);
                const unsigned   idx = (k * n_q + q) * n_tools + t;
                const bool   rough   = friction_on && friction_laws[t].mu > 0.;
                Tensor<1, 3> delta;
                const ContactResponse r =
                  respond(idx, t, g, eps, n, u_values[q] - u_old[q], delta);
                const double       p       = r.pressure;
                const unsigned int point   = k * n_q + q;
                const bool         pressed = record(r,
                                            g,
                                            n,
                                            delta,
                                            t,
                                            eps,
                                            JxW,
                                            cell->material_id(),
                                            &point,
                                            &point + 1,
                                            out,
                                            result);
                const bool         predicted =
                  (p <= 0. && out.matrix != nullptr && g < out.tangent_margin);
                if (!pressed && !predicted)
                  continue;
                if (!have_phi)
                  {
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      if (plain)
                        {
                          phi[i]                      = Tensor<1, 3>();
                          phi[i][tables.component(i)] = tables.shape(k, i, q);
                        }
                      else
                        phi[i] = (*fe_face)[u].value(i, q);
                    have_phi = true;
                  }
                if (predicted)
                  {
                    // near contact: stiffness in the tangent only (predictor)
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      {
                        const double n_phi_i = n * phi[i];
                        for (unsigned int j = 0; j < n_dofs; ++j)
                          cell_matrix(i, j) +=
                            eps * n_phi_i * (n * phi[j]) * JxW;
                      }
                    touched = true;
                    continue;
                  }
                const Tensor<1, 3> traction = p * n + r.traction;
                p_sum += p;
                if (rough)
                  {
                    slip_sum += accumulated_slip[idx];
                    status_max =
                      std::max(status_max, static_cast<double>(r.status));
                  }
                else
                  status_max = std::max(status_max, 2.);
                if (out.residual == nullptr)
                  continue;
                touched = true;
                for (unsigned int i = 0; i < n_dofs; ++i)
                  cell_residual(i) -= (traction * phi[i]) * JxW;
                if (out.matrix == nullptr)
                  continue;
                for (unsigned int j = 0; j < n_dofs; ++j)
                  D_phi[j] = r.stiffness * phi[j];
                for (unsigned int i = 0; i < n_dofs; ++i)
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += (phi[i] * D_phi[j]) * JxW;
                if (curvature > 0)
                  // concave die wall: p d(n)/dx = p/r (I_h - e_r e_r), PSD
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      {
                        const double horizontal =
                          phi[i][0] * phi[j][0] + phi[i][1] * phi[j][1];
                        cell_matrix(i, j) +=
                          p * curvature *
                          (horizontal - (n * phi[i]) * (n * phi[j])) * JxW;
                      }
                if (curvature > 0 && rough && friction_laws[t].consistent)
                  {
                    // the friction traction turns with the normal too:
                    // dn = -(1/r) (I_h - n n) dx (doc/theory.md section 8);
                    // not symmetric, so only with the consistent tangent
                    const FrictionTerms terms =
                      friction_terms(r,
                                     n,
                                     committed_traction[idx],
                                     delta,
                                     friction_laws[t].tangential_ratio * eps,
                                     friction_laws[t]);
                    for (unsigned int j = 0; j < n_dofs; ++j)
                      {
                        Tensor<1, 3> dn;
                        dn[0] = phi[j][0];
                        dn[1] = phi[j][1];
                        dn    = -curvature * (dn - (n * dn) * n);
                        const Tensor<1, 3> dt = friction_traction_change(
                          terms, n, dn, Tensor<1, 3>(), 0.);
                        for (unsigned int i = 0; i < n_dofs; ++i)
                          cell_matrix(i, j) -= (phi[i] * dt) * JxW;
                      }
                  }
              }
            if (post_face)
              for (unsigned int i = 0; i < post_indices.size(); ++i)
                {
                  const double v = post_face->shape_value(i, q) * JxW;
                  post_p(i) += v * p_sum;
                  post_slip(i) += v * slip_sum;
                  post_status(i) += v * status_max;
                  post_weights(i) += v;
                }
          }
        if (post_face)
          add_surface_field_values(post_indices,
                                   post_p,
                                   post_slip,
                                   post_status,
                                   post_weights,
                                   *out.sums);
        if (touched && plain)
          for (unsigned int i = 0; i < n_dofs; ++i)
            out.plain_residual->add(tables.dofs(k)[i], cell_residual(i));
        else if (touched)
          {
            cell->get_dof_indices(dof_indices);
            out.residual->add(dof_indices, cell_residual);
            if (out.matrix != nullptr)
              out.matrix->add(dof_indices, cell_matrix);
          }
      }

    const MPI_Comm comm = dof_handler->get_communicator();
    for (unsigned int t = 0; t < n_tool_kinds; ++t)
      {
        result.normal_force[t] =
          Utilities::MPI::sum(result.normal_force[t], comm);
        result.axial_force[t] =
          Utilities::MPI::sum(result.axial_force[t], comm);
        result.friction_force[t] =
          Utilities::MPI::sum(result.friction_force[t], comm);
      }
    result.max_penetration = Utilities::MPI::max(result.max_penetration, comm);
    result.friction_work   = Utilities::MPI::sum(result.friction_work, comm);
    result.elastic_energy  = Utilities::MPI::sum(result.elastic_energy, comm);
    result.multiplier_work = Utilities::MPI::sum(result.multiplier_work, comm);
    result.n_active        = Utilities::MPI::sum(result.n_active, comm);
    result.n_slip          = Utilities::MPI::sum(result.n_slip, comm);
    return result;
  }



  ContactResponse
  ToolContact::respond(const unsigned int  idx,
                       const unsigned int  t,
                       const double        g,
                       const double        eps,
                       const Tensor<1, 3> &n,
                       const Tensor<1, 3> &motion,
                       Tensor<1, 3>       &delta) const
  {
    const bool rough = has_friction() && friction_laws[t].mu > 0.;
    // the law of a frictionless point, built once (no copy per point)
    static const FrictionLaw frictionless;
    const FrictionLaw       &law = rough ? friction_laws[t] : frictionless;
    // relative motion since the last accepted increment
    delta = rough ? Tensor<1, 3>(motion - (shift[t] - committed_shift[t])) :
                    Tensor<1, 3>();
    return evaluate_contact_law(
      lambda[idx],
      g,
      eps,
      n,
      rough ? committed_traction[idx] : Tensor<1, 3>(),
      delta,
      (rough ? friction_laws[t].tangential_ratio : 1.) * eps,
      law);
  }



  bool
  ToolContact::record(const ContactResponse &r,
                      const double           g,
                      const Tensor<1, 3>    &n,
                      const Tensor<1, 3>    &delta,
                      const unsigned int     t,
                      const double           eps,
                      const double           JxW,
                      const unsigned int     material,
                      const unsigned int    *copy_first,
                      const unsigned int    *copy_last,
                      const Outputs         &out,
                      ToolContactResult     &result) const
  {
    const unsigned int n_tools = tool_list.size();
    const unsigned int idx     = *copy_first * n_tools + t;
    const bool         rough   = has_friction() && friction_laws[t].mu > 0.;
    const double       p       = r.pressure;
    if (out.new_lambda != nullptr)
      {
        for (const unsigned int *c = copy_first; c != copy_last; ++c)
          (*out.new_lambda)[*c * n_tools + t] = p;
        // d(p^2 / 2 eps) / d lambda times the multiplier's change per unit
        // relaxation
        result.multiplier_work += p / eps * (p - lambda[idx]) * JxW;
      }
    if (out.new_traction != nullptr && rough)
      {
        const Tensor<1, 3> slip = delta - (delta * n) * n;
        for (const unsigned int *c = copy_first; c != copy_last; ++c)
          {
            (*out.new_traction)[*c * n_tools + t] = r.traction;
            if (r.status == ContactStatus::slip)
              (*out.new_slip)[*c * n_tools + t] += slip.norm();
          }
        // the traction opposes the slip beyond a stick spring's elastic slip
        result.friction_work -=
          (r.traction * friction_laws[t].dissipating_slip(
                          slip, r.traction, committed_traction[idx], eps)) *
          JxW;
      }
    result.max_penetration = std::max(result.max_penetration, -g);
    if (p <= 0.)
      return false;
    const RigidTool &tool = tool_list[t];
    if (out.particle_force != nullptr && tool.kind == out.force_kind)
      (*out.particle_force)[material] += p * JxW;
    result.n_active += copy_last - copy_first;
    if (r.status == ContactStatus::slip && rough)
      result.n_slip += copy_last - copy_first;
    const unsigned int kind = static_cast<unsigned int>(tool.kind);
    result.elastic_energy +=
      friction_laws[t].elastic_energy(r, eps, rough) * JxW;
    result.normal_force[kind] += p * JxW;
    result.axial_force[kind] += (p * n + r.traction)[2] * JxW;
    result.friction_force[kind] += r.traction * JxW;
    return true;
  }



  bool
  ToolContact::vertex_pass(const Outputs &out, ToolContactResult &result) const
  {
    const unsigned int n_q     = face_quadrature.size();
    const unsigned int n_tools = tool_list.size();
    if (!vertices.checked)
      {
        // each slave point's corner (its reference position is the
        // corner's), the points ordered by their vertex (its first DoF)
        vertices.checked = true;
        std::vector<std::array<types::global_dof_index, 3>> order;
        for (unsigned int k = 0; k < faces.size(); ++k)
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const double size =
                (face_vertices[3 * k + 1] - face_vertices[3 * k]).norm();
              unsigned int corner = numbers::invalid_unsigned_int;
              for (unsigned int v = 0; v < 3; ++v)
                if ((tables.point(k, q) - face_vertices[3 * k + v]).norm() <=
                    1e-12 * size)
                  corner = v;
              if (corner == numbers::invalid_unsigned_int ||
                  dof_handler->get_fe().degree != 1)
                return false;
              order.push_back(
                {{face_vertex_dofs[9 * k + 3 * corner], k * n_q + q, corner}});
            }
        std::sort(order.begin(), order.end());
        vertices.copy_start.assign(1, 0);
        for (unsigned int a = 0, b = 0; a < order.size(); a = b)
          {
            const unsigned int k = order[a][1] / n_q, v = order[a][2];
            vertices.position.push_back(face_vertices[3 * k + v]);
            vertices.dofs.push_back({{face_vertex_dofs[9 * k + 3 * v],
                                      face_vertex_dofs[9 * k + 3 * v + 1],
                                      face_vertex_dofs[9 * k + 3 * v + 2]}});
            vertices.material.push_back(faces[k].first->material_id());
            double weight = 0.;
            for (b = a; b < order.size() && order[b][0] == order[a][0]; ++b)
              {
                vertices.copies.push_back(order[b][1]);
                weight += tables.JxW(order[b][1] / n_q, order[b][1] % n_q);
              }
            vertices.copy_start.push_back(vertices.copies.size());
            vertices.weight.push_back(weight);
          }
      }
    if (vertices.position.empty() && !faces.empty())
      return false;

    const bool friction_on = has_friction();
    for (unsigned int j = 0; j < vertices.position.size(); ++j)
      {
        const auto  &dofs = vertices.dofs[j];
        Tensor<1, 3> u, u_old;
        for (unsigned int d = 0; d < 3; ++d)
          {
            u[d] = (*out.values)[dofs[d]];
            if (friction_on)
              u_old[d] = (*out.committed_values)[dofs[d]];
          }
        const Point<3>      x   = vertices.position[j] + u;
        const double        eps = penalty[vertices.material[j]];
        const double        JxW = vertices.weight[j];
        const unsigned int *first =
                             vertices.copies.data() + vertices.copy_start[j],
                           *last = vertices.copies.data() +
                                   vertices.copy_start[j + 1];
        for (unsigned int t = 0; t < n_tools; ++t)
          {
            Tensor<1, 3>       n;
            double             curvature;
            const double       g   = tool_list[t].gap(x, n, curvature);
            const unsigned int idx = *first * n_tools + t;
            // open: no pressure, no traction (the outputs arrive zeroed)
            if (g > lambda[idx] / eps)
              continue;
            Tensor<1, 3>          delta;
            const ContactResponse r =
              respond(idx, t, g, eps, n, u - u_old, delta);
            if (record(r,
                       g,
                       n,
                       delta,
                       t,
                       eps,
                       JxW,
                       vertices.material[j],
                       first,
                       last,
                       out,
                       result) &&
                out.residual != nullptr)
              {
                const Tensor<1, 3> traction = r.pressure * n + r.traction;
                for (unsigned int d = 0; d < 3; ++d)
                  out.plain_residual->add(dofs[d], -traction[d] * JxW);
              }
          }
      }
    return true;
  }



  ToolContactResult
  ToolContact::pass(const Mapping<3>                    &mapping,
                    const TrilinosWrappers::MPI::Vector &solution,
                    const ContactOutputs                &common) const
  {
    Outputs out;
    static_cast<ContactOutputs &>(out) = common;
    return loop(mapping, solution, out);
  }



  std::vector<double>
  ToolContact::particle_forces(const Mapping<3>                    &mapping,
                               const TrilinosWrappers::MPI::Vector &solution,
                               const ToolKind                       kind) const
  {
    std::vector<double> force(penalty.size(), 0.);
    Outputs             out;
    out.particle_force = &force;
    out.force_kind     = kind;
    loop(mapping, solution, out);
    Utilities::MPI::sum(force, dof_handler->get_communicator(), force);
    return force;
  }



  void
  ToolContact::project_fields(const Mapping<3>                    &mapping,
                              const TrilinosWrappers::MPI::Vector &solution,
                              const DoFHandler<3> &post_dof_handler,
                              SurfaceFieldSums    &sums) const
  {
    Outputs out;
    out.post = &post_dof_handler;
    out.sums = &sums;
    loop(mapping, solution, out);
  }
} // namespace densify
