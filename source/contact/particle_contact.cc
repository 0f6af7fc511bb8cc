// Augmented-Lagrangian contact with Coulomb friction between the surfaces of
// deformable particles.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/fe/fe_values.h>

#include <densify/contact/closest_point.h>
#include <densify/contact/geometric_tangent.h>
#include <densify/contact/particle_contact.h>

#include <boost/container/small_vector.hpp>

#include <algorithm>
#include <array>
#include <iterator>
#include <limits>

namespace densify
{
  namespace
  {
    /// The vertices of the reference tetrahedron.
    const std::array<Point<3>, 4> reference_vertices = {{Point<3>(0, 0, 0),
                                                         Point<3>(1, 0, 0),
                                                         Point<3>(0, 1, 0),
                                                         Point<3>(0, 0, 1)}};

  } // namespace



  ParticleContact::Projection
  ParticleContact::project(const Point<3>              &x,
                           const unsigned int           m,
                           const std::vector<Point<3>> &vertices,
                           const double                 band,
                           double                      &distance_squared,
                           const bool                   with_normal) const
  {
    const Facet            &facet = facets[m];
    std::array<Point<3>, 4> c;
    for (unsigned int k = 0; k < 4; ++k)
      c[k] = vertices[facet.vertex[k]];
    Projection result;
    result.facet = m;
    if (band == 0.)
      result.bary = closest_on_triangle(x, c[0], c[1], c[2]);
    else
      {
        // the triangle scaled by s about its centroid g: a point with
        // coordinates b' there has b = s b' - band here
        const double                s = 1. + 3. * band;
        const Point<3>              g((c[0][0] + c[1][0] + c[2][0]) / 3.,
                         (c[0][1] + c[1][1] + c[2][1]) / 3.,
                         (c[0][2] + c[1][2] + c[2][2]) / 3.);
        const std::array<double, 3> b = closest_on_triangle(x,
                                                            g + s * (c[0] - g),
                                                            g + s * (c[1] - g),
                                                            g + s * (c[2] - g));
        for (unsigned int k = 0; k < 3; ++k)
          result.bary[k] = s * b[k] - band;
      }
    const Point<3> y =
      result.bary[0] * c[0] + result.bary[1] * c[1] + result.bary[2] * c[2];
    distance_squared = (x - y).norm_square();
    if (with_normal)
      result.normal = outward_normal(m, vertices);
    return result;
  }



  Tensor<1, 3>
  ParticleContact::outward_normal(const unsigned int           m,
                                  const std::vector<Point<3>> &vertices) const
  {
    const Facet            &facet = facets[m];
    std::array<Point<3>, 4> c;
    for (unsigned int k = 0; k < 4; ++k)
      c[k] = vertices[facet.vertex[k]];
    Tensor<1, 3> n = cross_product_3d(c[1] - c[0], c[2] - c[0]);
    if (n * (c[3] - c[0]) > 0)
      n = -n;
    return n / n.norm();
  }



  ParticleContact::Projection
  ParticleContact::choose_facet(const Point<3>              &x,
                                const unsigned int          *first,
                                const unsigned int          *last,
                                const std::vector<Point<3>> &vertices,
                                double                      &distance_squared,
                                const unsigned int           particle) const
  {
    bool only_particle = false;
    if (particle != numbers::invalid_unsigned_int)
      for (const unsigned int *c = first; c != last && !only_particle; ++c)
        only_particle = facets[*c].particle == particle;
    // each particle's closest facet (its normal once chosen); a point meets
    // few particles, so a short list
    struct Offer
    {
      unsigned int particle;
      double       d2;
      Projection   projection;
    };
    boost::container::small_vector<Offer, 8> offers;
    for (const unsigned int *c = first; c != last; ++c)
      {
        const unsigned int p = facets[*c].particle;
        if (only_particle && p != particle)
          continue;
        double           d2;
        const Projection pr = project(x, *c, vertices, 0., d2, false);
        auto             o  = offers.begin();
        while (o != offers.end() && o->particle != p)
          ++o;
        if (o == offers.end())
          offers.push_back({p, d2, pr});
        else if (d2 < o->d2)
          {
            o->d2         = d2;
            o->projection = pr;
          }
      }
    distance_squared = std::numeric_limits<double>::max();
    if (offers.empty())
      return Projection();
    // the closest offer, unless the point lies behind some particle's
    // closest facet: then the deepest such (the signed distance to the
    // facet plus the distance beside it, as the gap of loop())
    const Offer *chosen = nullptr, *inside = nullptr;
    double       depth = 0.;
    for (const Offer &o : offers)
      {
        if (chosen == nullptr || o.d2 < chosen->d2)
          chosen = &o;
        if (offers.size() > 1)
          {
            const Tensor<1, 3> n = outward_normal(o.projection.facet, vertices);
            const Facet       &f = facets[o.projection.facet];
            Point<3>           y;
            for (unsigned int a = 0; a < 3; ++a)
              y += o.projection.bary[a] * vertices[f.vertex[a]];
            const Tensor<1, 3> d   = x - y;
            const double       g_n = d * n;
            const double       g   = g_n + (d - g_n * n).norm();
            if (g < depth)
              {
                depth  = g;
                inside = &o;
              }
          }
      }
    if (inside != nullptr)
      chosen = inside;
    Projection best  = chosen->projection;
    best.normal      = outward_normal(best.facet, vertices);
    distance_squared = chosen->d2;
    return best;
  }



  ParticleContactResult
  ParticleContact::loop(const Mapping<3>                    &mapping,
                        const TrilinosWrappers::MPI::Vector &solution,
                        const Outputs                       &out) const
  {
    ParticleContactResult result;
    const MPI_Comm        comm = dof_handler->get_communicator();
    result.n_candidate_pairs   = broad_search.pairs().size();

    const bool friction_on = friction.mu > 0.;
    Assert(!friction_on || committed_solution != nullptr,
           ExcMessage("friction needs set_committed_solution()"));
    const FiniteElement<3> &fe     = dof_handler->get_fe();
    const unsigned int      n_q    = face_quadrature.size();
    const unsigned int      n_dofs = fe.n_dofs_per_cell();
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
    else if (!tables.ready())
      {
        std::vector<
          std::pair<DoFHandler<3>::active_cell_iterator, unsigned int>>
          faces;
        for (const unsigned int m : slave_faces)
          faces.emplace_back(facets[m].cell, facets[m].face);
        tables.reinit(mapping, fe, face_quadrature, faces);
      }
    std::unique_ptr<FEFaceValues<3>> post_face;
    if (out.post != nullptr)
      post_face =
        std::make_unique<FEFaceValues<3>>(mapping,
                                          out.post->get_fe(),
                                          face_quadrature,
                                          update_values | update_JxW_values);
    std::vector<Point<3>> x_accessed;
    if (!plain)
      x_accessed = current_vertices(solution);
    const std::vector<Point<3>> &x_now =
      plain ? current_vertices(*out.values) : x_accessed;
    // the explicit pass searches each point's near list (the same facet as
    // all candidates give); a pass that assigns facets searches them all
    const bool use_lists =
      plain && out.new_assignment == nullptr && near.enabled;
    if (use_lists)
      update_near_lists(x_now, *out.values);
    // each surface vertex once for all its slave points (NearLists)
    const bool by_vertex = use_lists && near.by_vertex && near.at_corners;
    const auto evaluated = [&](const unsigned int idx) {
      return !by_vertex || near.copy_start[idx] < near.copy_start[idx + 1];
    };
    std::vector<char> pressed(by_vertex ? slave_faces.size() * n_q : 0, 0);
    // the slave facet's current over its reference area (flat), from the
    // facet's own vertex indices and reference positions
    const auto area_ratio_of = [&](const Facet &slave) {
      const auto area = [](const Tensor<1, 3> &e1, const Tensor<1, 3> &e2) {
        return cross_product_3d(e1, e2).norm();
      };
      return area(x_now[slave.vertex[1]] - x_now[slave.vertex[0]],
                  x_now[slave.vertex[2]] - x_now[slave.vertex[0]]) /
             area(slave.position[1] - slave.position[0],
                  slave.position[2] - slave.position[0]);
    };
    // the scalar shape functions of the base element behind each vector
    // one (the same values as fe.shape_value(), a third of the calls)
    std::vector<unsigned int> base_index(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      base_index[i] = fe.system_to_base_index(i).second;
    const FiniteElement<3>   &base = fe.base_element(0);
    std::vector<double>       base_phi(base.n_dofs_per_cell());
    std::vector<unsigned int> component(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = fe.system_to_component_index(i).first;

    const FEValuesExtractors::Vector     u(0);
    std::vector<Tensor<1, 3>>            u_values(n_q), u_old(n_q);
    std::vector<Tensor<1, 3>>            psi(2 * n_dofs), D_psi(2 * n_dofs);
    Vector<double>                       master_u(n_dofs), master_old(n_dofs);
    std::vector<double>                  master_phi(n_dofs);
    std::vector<int>                     corner(n_dofs);
    std::vector<Tensor<1, 3>>            master_grad(n_dofs);
    FullMatrix<double>                   pair_matrix(2 * n_dofs, 2 * n_dofs);
    Vector<double>                       pair_residual(2 * n_dofs);
    std::vector<types::global_dof_index> pair_dofs(2 * n_dofs),
      master_dofs(n_dofs);
    std::vector<types::global_dof_index> post_indices;
    Vector<double> post_p, post_slip, post_status, post_weights;
    // two passes, each surface slave once: weight 1/2
    const double weight = 0.5;

    for (unsigned int k = 0; k < slave_faces.size(); ++k)
      {
        const unsigned int begin = candidate_start[k],
                           end   = candidate_start[k + 1];
        if (begin == end && post_face == nullptr)
          continue;
        const Facet &slave = facets[slave_faces[k]];
        if (!plain)
          fe_face->reinit(slave.cell, slave.face);
        if (post_face)
          {
            const typename DoFHandler<3>::active_cell_iterator post_cell(
              &slave.cell->get_triangulation(),
              slave.cell->level(),
              slave.cell->index(),
              out.post);
            post_face->reinit(post_cell, slave.face);
            const unsigned int n_post = post_face->get_fe().n_dofs_per_cell();
            post_indices.resize(n_post);
            post_cell->get_dof_indices(post_indices);
            for (auto *v : {&post_p, &post_slip, &post_status, &post_weights})
              v->reinit(n_post);
          }
        // whether one of the facet's points carries a pressure
        bool face_in_contact = false;
        bool face_evaluated  = false;
        bool old_pending     = false;
        for (unsigned int q = 0; q < n_q; ++q)
          face_evaluated = face_evaluated || evaluated(k * n_q + q);
        if (begin < end && face_evaluated)
          {
            if (plain)
              {
                tables.values(k, *out.values, u_values);
                // the committed values once a point of the face is evaluated
                // in full (below)
                old_pending = friction_on;
                std::copy(tables.dofs(k),
                          tables.dofs(k) + n_dofs,
                          pair_dofs.begin());
              }
            else
              {
                (*fe_face)[u].get_function_values(solution, u_values);
                if (friction_on)
                  (*fe_face)[u].get_function_values(*committed_solution, u_old);
                slave.cell->get_dof_indices(master_dofs);
                std::copy(master_dofs.begin(),
                          master_dofs.end(),
                          pair_dofs.begin());
              }
          }
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const unsigned int idx = k * n_q + q;
            // by vertex: the weight of all the vertex's slave points
            const double JxW   = by_vertex ? near.weight[idx] :
                                 plain     ? tables.JxW(k, q) :
                                             fe_face->JxW(q);
            double       p_out = 0, slip_out = 0, status_out = 0;
            // the slave points whose traction this evaluation gives
            const unsigned int *copy_first =
                                 by_vertex ?
                                   near.copies.data() + near.copy_start[idx] :
                                   &idx,
                               *copy_last = by_vertex ?
                                              near.copies.data() +
                                                near.copy_start[idx + 1] :
                                              &idx + 1;
            if (begin < end && evaluated(idx))
              {
                const Point<3> x_s =
                  (plain ? tables.point(k, q) : fe_face->quadrature_point(q)) +
                  u_values[q];
                const unsigned int kept =
                  (out.new_assignment != nullptr || assigned.empty()) ?
                    numbers::invalid_unsigned_int :
                    assigned[idx];
                Projection best;
                double     best_distance = std::numeric_limits<double>::max();
                if (kept != numbers::invalid_unsigned_int)
                  best = project(x_s,
                                 kept,
                                 x_now,
                                 assigned_in_band[idx] ? projection_band : 0.,
                                 best_distance);
                else
                  {
                    const unsigned int *first =
                      use_lists ? near.facets.data() + near.start[idx] :
                                  candidates.data() + begin;
                    const unsigned int *last =
                      use_lists ? near.facets.data() + near.start[idx + 1] :
                                  candidates.data() + end;
                    // a point keeps its particle within a Newton solve
                    const unsigned int old = assigned[idx];
                    const unsigned int particle =
                      (out.new_assignment != nullptr &&
                       old != numbers::invalid_unsigned_int) ?
                        facets[old].particle :
                        numbers::invalid_unsigned_int;
                    best = choose_facet(
                      x_s, first, last, x_now, best_distance, particle);
                    // the closest facet, measured to its enlargement only
                    // where the point projects into it
                    const auto inside_of = [](const Projection &pr) {
                      return std::min({pr.bary[0], pr.bary[1], pr.bary[2]});
                    };
                    bool in_band = inside_of(best) > 0.;
                    if (out.new_assignment != nullptr &&
                        old != numbers::invalid_unsigned_int &&
                        facets[old].particle == facets[best.facet].particle)
                      {
                        // hysteresis: keep the old facet of the same particle
                        // while the point projects into it enlarged by the
                        // band, and no other facet is closer by more than
                        // that band
                        bool             keep = old == best.facet;
                        double           d2;
                        const Projection banded =
                          project(x_s, old, x_now, projection_band, d2);
                        if (!keep)
                          {
                            double size = 0;
                            for (unsigned int a = 0; a < 3; ++a)
                              size = std::max(
                                size,
                                (x_now[facets[old].cell->vertex_index(
                                   facets[old].local_vertex[a])] -
                                 x_now[facets[old].cell->vertex_index(
                                   facets[old].local_vertex[(a + 1) % 3])])
                                  .norm());
                            keep = inside_of(banded) >
                                     -projection_band * (1. - 1e-9) &&
                                   std::sqrt(d2) <= std::sqrt(best_distance) +
                                                      projection_band * size;
                          }
                        // a kept facet is measured as the evaluations since
                        // its assignment measured it: to its enlargement
                        // once the point has projected into it
                        if (keep)
                          {
                            const Projection itself =
                              old == best.facet ?
                                best :
                                project(x_s, old, x_now, 0., d2);
                            in_band = assigned_in_band[idx] != 0 ||
                                      inside_of(itself) > 0.;
                            best = in_band ? banded : itself;
                          }
                      }
                    if (out.new_assignment != nullptr)
                      {
                        (*out.new_assignment)[idx] = best.facet;
                        (*out.new_in_band)[idx]    = in_band;
                      }
                  }
                const Facet        &master = facets[best.facet];
                const Tensor<1, 3> &n      = best.normal;
                // the point's offset from its projection on the facet's
                // current corners
                const Tensor<1, 3> off =
                  x_s - (best.bary[0] * x_now[master.vertex[0]] +
                         best.bary[1] * x_now[master.vertex[1]] +
                         best.bary[2] * x_now[master.vertex[2]]);
                const double eps =
                  std::min(penalty[slave.particle], penalty[master.particle]);
                // linear: the master point is those corners at the
                // projection, so the gap below follows from the offset
                // alone; a point open by more than round-off gives no
                // force, no pressure and no traction (the outputs arrive
                // zeroed), and the rest of its evaluation is skipped
                if (plain && base.degree == 1 && out.matrix == nullptr &&
                    post_face == nullptr &&
                    off * n + (off - (off * n) * n).norm() >
                      lambda[idx] / eps + 1e-12 * (1. + x_s.norm()))
                  continue;
                // master point and displacement by the master's shape
                // functions at the projection
                Point<3> xi;
                for (unsigned int a = 0; a < 3; ++a)
                  xi +=
                    best.bary[a] * reference_vertices[master.local_vertex[a]];
                const types::global_dof_index *m_dofs =
                  &facet_dofs[std::size_t(best.facet) * n_dofs];
                if (plain)
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    master_u(i) = (*out.values)[m_dofs[i]];
                else
                  master.cell->get_dof_values(solution, master_u);
                Point<3> X_m;
                for (unsigned int a = 0; a < 3; ++a)
                  X_m += best.bary[a] * master.position[a];
                Tensor<1, 3> u_m, u_m_old;
                if (plain && base.degree == 1)
                  {
                    // linear: the shape function of each vertex is its
                    // barycentric coordinate, zero at the facet's fourth
                    std::fill(base_phi.begin(), base_phi.end(), 0.);
                    for (unsigned int a = 0; a < 3; ++a)
                      base_phi[master.local_vertex[a]] = best.bary[a];
                  }
                else if (plain)
                  for (unsigned int b = 0; b < base_phi.size(); ++b)
                    base_phi[b] = base.shape_value(b, xi);
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    master_phi[i] =
                      plain ? base_phi[base_index[i]] : fe.shape_value(i, xi);
                    u_m[component[i]] += master_u(i) * master_phi[i];
                  }
                if (old_pending)
                  {
                    tables.values(k, *out.committed_values, u_old);
                    old_pending = false;
                  }
                if (friction_on)
                  {
                    if (plain)
                      for (unsigned int i = 0; i < n_dofs; ++i)
                        master_old(i) = (*out.committed_values)[m_dofs[i]];
                    else
                      master.cell->get_dof_values(*committed_solution,
                                                  master_old);
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      u_m_old[component[i]] += master_old(i) * master_phi[i];
                  }
                // the normal gap, plus how far the point lies beside the
                // (enlarged) facet: a point beyond the facet's edges, for
                // example in the plane of a neighbour's facet flattened
                // against the same punch, is not in contact with it. Zero for
                // every point that projects into the facet, and continuous
                // in the displacement (doc/theory.md section 9)
                const double g =
                  (x_s - (X_m + u_m)) * n + (off - (off * n) * n).norm();
                const Tensor<1, 3> delta =
                  friction_on ?
                    Tensor<1, 3>((u_values[q] - u_old[q]) - (u_m - u_m_old)) :
                    Tensor<1, 3>();
                const ContactResponse r =
                  evaluate_contact_law(lambda[idx],
                                       g,
                                       eps,
                                       n,
                                       friction_on ? committed_traction[idx] :
                                                     Tensor<1, 3>(),
                                       delta,
                                       friction.tangential_ratio * eps,
                                       friction);
                const double p = r.pressure;
                if (out.n_changed != nullptr && p > 0. &&
                    assigned[idx] != best.facet)
                  ++(*out.n_changed);
                if (out.new_lambda != nullptr)
                  {
                    for (const unsigned int *c = copy_first; c != copy_last;
                         ++c)
                      (*out.new_lambda)[*c] = p;
                    // d(p^2 / 2 eps) / d lambda times the multiplier's
                    // change per unit relaxation
                    result.multiplier_work +=
                      weight * p / eps * (p - lambda[idx]) * JxW;
                  }
                if (out.new_traction != nullptr && friction_on)
                  {
                    const Tensor<1, 3> slip = delta - (delta * n) * n;
                    for (const unsigned int *c = copy_first; c != copy_last;
                         ++c)
                      {
                        (*out.new_traction)[*c] = r.traction;
                        if (r.status == ContactStatus::slip)
                          (*out.new_slip)[*c] += slip.norm();
                      }
                    // the traction opposes the slip beyond a stick
                    // spring's elastic slip
                    result.friction_work -=
                      weight *
                      (r.traction *
                       friction.dissipating_slip(
                         slip, r.traction, committed_traction[idx], eps)) *
                      JxW;
                  }
                result.max_penetration = std::max(result.max_penetration, -g);
                face_in_contact        = face_in_contact || p > 0.;
                if (by_vertex && p > 0.)
                  for (const unsigned int *c = copy_first; c != copy_last; ++c)
                    pressed[*c] = 1;
                const bool predicted =
                  (p <= 0. && out.matrix != nullptr && g < out.tangent_margin);
                if (p > 0. || predicted)
                  {
                    // relative shape functions: slave phi, minus master phi
                    std::copy(m_dofs, m_dofs + n_dofs, master_dofs.begin());
                    std::copy(master_dofs.begin(),
                              master_dofs.end(),
                              pair_dofs.begin() + n_dofs);
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      {
                        if (plain)
                          {
                            psi[i]               = Tensor<1, 3>();
                            psi[i][component[i]] = tables.shape(k, i, q);
                          }
                        else
                          psi[i] = (*fe_face)[u].value(i, q);
                        psi[n_dofs + i]               = Tensor<1, 3>();
                        psi[n_dofs + i][component[i]] = -master_phi[i];
                      }
                    if (p > 0.)
                      {
                        result.n_active += copy_last - copy_first;
                        if (friction_on && r.status == ContactStatus::slip)
                          result.n_slip += copy_last - copy_first;
                        result.normal_force += weight * p * JxW;
                        result.elastic_energy +=
                          weight *
                          friction.elastic_energy(r, eps, friction_on) * JxW;
                        result.friction_force +=
                          weight * r.traction.norm() * JxW;
                        p_out      = p;
                        slip_out   = friction_on ? accumulated_slip[idx] : 0.;
                        status_out = static_cast<double>(r.status);
                        if (out.pairs != nullptr)
                          out.pairs->emplace(
                            std::min(slave.particle, master.particle),
                            std::max(slave.particle, master.particle));
                        if (out.residual != nullptr)
                          {
                            // the traction acts on the slave and, opposite, on
                            // the master point: action = reaction
                            const Tensor<1, 3> traction = p * n + r.traction;
                            for (unsigned int i = 0; i < 2 * n_dofs; ++i)
                              pair_residual(i) =
                                -weight * (traction * psi[i]) * JxW;
                            if (plain)
                              for (unsigned int i = 0; i < 2 * n_dofs; ++i)
                                out.plain_residual->add(pair_dofs[i],
                                                        pair_residual(i));
                            else
                              out.residual->add(pair_dofs, pair_residual);
                          }
                      }
                    if (out.matrix != nullptr)
                      {
                        // predicted contacts: normal stiffness in the tangent
                        // only
                        const Tensor<2, 3> D =
                          (p > 0. ? r.stiffness : eps * outer_product(n, n));
                        for (unsigned int j = 0; j < 2 * n_dofs; ++j)
                          D_psi[j] = D * psi[j];
                        for (unsigned int i = 0; i < 2 * n_dofs; ++i)
                          for (unsigned int j = 0; j < 2 * n_dofs; ++j)
                            pair_matrix(i, j) =
                              weight * (psi[i] * D_psi[j]) * JxW;
                        if (geometric_tangent && p > 0.)
                          {
                            std::array<Point<3>, 3> c, ref_corner;
                            for (unsigned int a = 0; a < 3; ++a)
                              {
                                c[a] = x_now[master.cell->vertex_index(
                                  master.local_vertex[a])];
                                ref_corner[a] =
                                  reference_vertices[master.local_vertex[a]];
                              }
                            for (unsigned int i = 0; i < n_dofs; ++i)
                              {
                                corner[i] = -1;
                                for (unsigned int a = 0; a < 3; ++a)
                                  if (master_dofs[i] ==
                                      master.cell->vertex_dof_index(
                                        master.local_vertex[a], component[i]))
                                    corner[i] = a;
                                master_grad[i] = fe.shape_grad(i, xi);
                              }
                            // d x_m / d xi: the affine cell map plus the
                            // displacement's reference gradient
                            Tensor<2, 3> dx_m_dxi;
                            for (unsigned int k = 0; k < 3; ++k)
                              for (unsigned int d = 0; d < 3; ++d)
                                dx_m_dxi[d][k] = master.cell->vertex(k + 1)[d] -
                                                 master.cell->vertex(0)[d];
                            for (unsigned int i = 0; i < n_dofs; ++i)
                              for (unsigned int k = 0; k < 3; ++k)
                                dx_m_dxi[component[i]][k] +=
                                  master_u(i) * master_grad[i][k];
                            // the projection slides with the points unless
                            // it is held at the edge of the (enlarged) facet
                            const Point<3> y = best.bary[0] * c[0] +
                                               best.bary[1] * c[1] +
                                               best.bary[2] * c[2];
                            const Tensor<1, 3> off = x_s - y;
                            const bool sliding = (off - (off * n) * n).norm() <=
                                                 1e-8 * (c[1] - c[0]).norm();
                            FrictionTerms terms;
                            Tensor<2, 3>  grad_delta_m;
                            if (friction_on)
                              {
                                terms =
                                  friction_terms(r,
                                                 n,
                                                 committed_traction[idx],
                                                 delta,
                                                 friction.tangential_ratio *
                                                   eps,
                                                 friction);
                                for (unsigned int i = 0; i < n_dofs; ++i)
                                  for (unsigned int kk = 0; kk < 3; ++kk)
                                    grad_delta_m[component[i]][kk] +=
                                      (master_u(i) - master_old(i)) *
                                      master_grad[i][kk];
                              }
                            add_geometric_tangent(c,
                                                  n,
                                                  off,
                                                  best.bary,
                                                  p,
                                                  p * n + r.traction,
                                                  sliding,
                                                  psi,
                                                  corner,
                                                  component,
                                                  master_grad,
                                                  ref_corner,
                                                  eps,
                                                  x_s - (X_m + u_m),
                                                  dx_m_dxi,
                                                  weight * JxW,
                                                  friction_on ? &terms :
                                                                nullptr,
                                                  grad_delta_m,
                                                  pair_matrix);
                          }
                        out.matrix->add(pair_dofs, pair_matrix);
                      }
                  }
              }
            if (post_face)
              for (unsigned int i = 0; i < post_indices.size(); ++i)
                {
                  const double v = post_face->shape_value(i, q) * JxW;
                  post_p(i) += v * p_out;
                  post_slip(i) += v * slip_out;
                  post_status(i) += v * status_out;
                  post_weights(i) += v;
                }
          }
        if (face_in_contact && !by_vertex)
          {
            const double ratio = area_ratio_of(slave);
            for (unsigned int q = 0; q < n_q; ++q)
              result.contact_area +=
                weight * ratio * (plain ? tables.JxW(k, q) : fe_face->JxW(q));
          }
        if (post_face)
          add_surface_field_values(post_indices,
                                   post_p,
                                   post_slip,
                                   post_status,
                                   post_weights,
                                   *out.sums);
      }

    // by vertex: the facets one of whose points carries a pressure
    if (by_vertex)
      for (unsigned int k = 0; k < slave_faces.size(); ++k)
        if (std::any_of(pressed.begin() + k * n_q,
                        pressed.begin() + (k + 1) * n_q,
                        [](const char c) { return c != 0; }))
          {
            const double ratio = area_ratio_of(facets[slave_faces[k]]);
            for (unsigned int q = 0; q < n_q; ++q)
              result.contact_area += weight * ratio * tables.JxW(k, q);
          }

    // one reduction for the sums (the counts are exact in doubles)
    std::array<double, 8> sums{{result.normal_force,
                                result.friction_force,
                                result.friction_work,
                                result.elastic_energy,
                                result.multiplier_work,
                                result.contact_area,
                                static_cast<double>(result.n_active),
                                static_cast<double>(result.n_slip)}};
    Utilities::MPI::sum(ArrayView<const double>(sums.data(), sums.size()),
                        comm,
                        ArrayView<double>(sums.data(), sums.size()));
    result.normal_force    = sums[0];
    result.friction_force  = sums[1];
    result.friction_work   = sums[2];
    result.elastic_energy  = sums[3];
    result.multiplier_work = sums[4];
    result.contact_area    = sums[5];
    result.n_active        = static_cast<unsigned int>(sums[6] + 0.5);
    result.n_slip          = static_cast<unsigned int>(sums[7] + 0.5);
    result.max_penetration = Utilities::MPI::max(result.max_penetration, comm);
    return result;
  }



  ParticleContactResult
  ParticleContact::pass(const Mapping<3>                    &mapping,
                        const TrilinosWrappers::MPI::Vector &solution,
                        const ContactOutputs                &common) const
  {
    Outputs out;
    static_cast<ContactOutputs &>(out) = common;
    return loop(mapping, solution, out);
  }



  unsigned int
  ParticleContact::update_projections(
    const Mapping<3>                    &mapping,
    const TrilinosWrappers::MPI::Vector &solution)
  {
    std::vector<unsigned int> new_assignment(assigned.size(),
                                             numbers::invalid_unsigned_int);
    std::vector<char>         new_in_band(assigned.size(), 1);
    unsigned int              n_changed = 0;
    Outputs                   out;
    out.new_assignment = &new_assignment;
    out.new_in_band    = &new_in_band;
    out.n_changed      = &n_changed;
    loop(mapping, solution, out);
    assigned.swap(new_assignment);
    assigned_in_band.swap(new_in_band);
    return Utilities::MPI::sum(n_changed, dof_handler->get_communicator());
  }



  std::vector<unsigned int>
  ParticleContact::contact_partners(
    const Mapping<3>                    &mapping,
    const TrilinosWrappers::MPI::Vector &solution) const
  {
    std::set<std::pair<unsigned int, unsigned int>> pairs;
    Outputs                                         out;
    out.pairs = &pairs;
    loop(mapping, solution, out);
    return partners_of(pairs);
  }



  std::vector<unsigned int>
  ParticleContact::partners_of(
    const std::set<std::pair<unsigned int, unsigned int>> &pairs) const
  {
    std::vector<unsigned int> flat;
    for (const auto &[a, b] : pairs)
      {
        flat.push_back(a);
        flat.push_back(b);
      }
    std::set<std::pair<unsigned, unsigned>> all;
    for (const auto &list :
         Utilities::MPI::all_gather(dof_handler->get_communicator(), flat))
      for (unsigned int i = 0; i + 1 < list.size(); i += 2)
        all.emplace(list[i], list[i + 1]);
    std::vector<unsigned int> partners(n_particles, 0);
    for (const auto &[a, b] : all)
      {
        ++partners[a];
        ++partners[b];
      }
    return partners;
  }



  void
  ParticleContact::project_fields(const Mapping<3>                    &mapping,
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
