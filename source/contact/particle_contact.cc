// Augmented-Lagrangian contact with Coulomb friction between the surfaces of
// deformable particles.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/fe/fe_values.h>

#include <densify/contact/particle_contact.h>

#include <algorithm>
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

    /**
     * Closest point of the triangle (a, b, c) to @p p as barycentric
     * coordinates (Ericson, Real-Time Collision Detection, 5.1.5).
     */
    std::array<double, 3>
    closest_on_triangle(const Point<3> &p,
                        const Point<3> &a,
                        const Point<3> &b,
                        const Point<3> &c)
    {
      const Tensor<1, 3> ab = b - a, ac = c - a, ap = p - a;
      const double       d1 = ab * ap, d2 = ac * ap;
      if (d1 <= 0 && d2 <= 0)
        return {{1., 0., 0.}};
      const Tensor<1, 3> bp = p - b;
      const double       d3 = ab * bp, d4 = ac * bp;
      if (d3 >= 0 && d4 <= d3)
        return {{0., 1., 0.}};
      const double vc = d1 * d4 - d3 * d2;
      if (vc <= 0 && d1 >= 0 && d3 <= 0)
        {
          const double v = d1 / (d1 - d3);
          return {{1 - v, v, 0.}};
        }
      const Tensor<1, 3> cp = p - c;
      const double       d5 = ab * cp, d6 = ac * cp;
      if (d6 >= 0 && d5 <= d6)
        return {{0., 0., 1.}};
      const double vb = d5 * d2 - d1 * d6;
      if (vb <= 0 && d2 >= 0 && d6 <= 0)
        {
          const double w = d2 / (d2 - d6);
          return {{1 - w, 0., w}};
        }
      const double va = d3 * d6 - d5 * d4;
      if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        {
          const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
          return {{0., 1 - w, w}};
        }
      const double denominator = 1. / (va + vb + vc);
      const double v = vb * denominator, w = vc * denominator;
      return {{1 - v - w, v, w}};
    }
    /**
     * Add to @p pair_matrix (slave DoFs, then master DoFs) the tangent terms
     * of the traction @p T = p n + t that come from the motion of the master
     * facet with corners @p c (current positions): the rotation of the
     * normal @p n, which turns the pressure @p p, and, if @p sliding, the
     * motion of the projection point (barycentric @p bary on the flat facet,
     * @p x_s_minus_y from there to the slave point), which moves @p T to
     * other master shape functions. For the flat facet y = c0 + b1 e1 + b2 e2
     * the projection condition (x_s - y) . e_a = 0 gives
     * M db = e_a . (dx_s - b_k dc_k) + (x_s - y) . de_a with the metric
     * M = e_a . e_b.
     * @p psi: slave shape functions and minus the master ones at the
     * projection; @p corner[i]: which facet corner the master DoF i moves
     * (-1: none); @p master_grad[i]: gradient of the master shape function i
     * in reference coordinates; @p ref_corner: the corners in reference
     * coordinates of the master cell. For P2 the master point
     * x_m (given by the master cell's shape functions) lies off the flat facet
     * through the corners: the gap g = (x_s - x_m) . n then also changes by
     * @p x_s_minus_x_m . dn - n . (@p dx_m_dxi dxi), which the pressure
     * p = lambda - @p eps g follows (both vanish for P1).
     * With friction (@p friction not null), the tangential traction t
     * follows the same motion: the tangent plane P = I - n n turns with n,
     * and the slip increment delta = du_s - du_m(xi) changes with the
     * projection point by -(@p grad_delta_m) dxi, with @p grad_delta_m the
     * gradient of the master's displacement increment by the master cell's
     * reference coordinates (FrictionTerms, friction_traction_change()).
     */
    void
    add_geometric_tangent(const std::array<Point<3>, 3>   &c,
                          const Tensor<1, 3>              &n,
                          const Tensor<1, 3>              &x_s_minus_y,
                          const std::array<double, 3>     &bary,
                          const double                     p,
                          const Tensor<1, 3>              &T,
                          const bool                       sliding,
                          const std::vector<Tensor<1, 3>> &psi,
                          const std::vector<int>          &corner,
                          const std::vector<unsigned int> &component,
                          const std::vector<Tensor<1, 3>> &master_grad,
                          const std::array<Point<3>, 3>   &ref_corner,
                          const double                     eps,
                          const Tensor<1, 3>              &x_s_minus_x_m,
                          const Tensor<2, 3>              &dx_m_dxi,
                          const double                     factor,
                          const FrictionTerms             *friction,
                          const Tensor<2, 3>              &grad_delta_m,
                          FullMatrix<double>              &pair_matrix)
    {
      const unsigned int n_dofs = component.size();
      const Tensor<1, 3> e1 = c[1] - c[0], e2 = c[2] - c[0];
      const Tensor<1, 3> normal_dir = cross_product_3d(e1, e2);
      const double       length     = normal_dir.norm();
      // n = sign c/|c|: dn = sign (I - n n) dc / |c|
      const double       sign = (normal_dir * n > 0) ? 1. : -1.;
      const Tensor<2, 3> P_n = unit_symmetric_tensor<3>() - outer_product(n, n);
      const double       m11 = e1 * e1, m12 = e1 * e2, m22 = e2 * e2;
      const double       det = m11 * m22 - m12 * m12;
      std::vector<Tensor<1, 3>> dn(2 * n_dofs), dxi(2 * n_dofs);
      std::vector<double>       dg(2 * n_dofs);
      for (unsigned int j = 0; j < 2 * n_dofs; ++j)
        {
          // the motion of the slave point relative to the flat facet's
          // point at fixed b: the slave's shape functions, minus b_a for the
          // corner DoFs (for P1 psi itself)
          const int    a = j < n_dofs ? -1 : corner[j - n_dofs];
          Tensor<1, 3> relative;
          if (j < n_dofs)
            relative = psi[j];
          else if (a >= 0)
            relative[component[j - n_dofs]] = -bary[a];
          double r1 = e1 * relative, r2 = e2 * relative;
          if (a >= 0)
            {
              Tensor<1, 3> e_d;
              e_d[component[j - n_dofs]] = 1.;
              const Tensor<1, 3> dc =
                a == 1 ? cross_product_3d(e_d, e2) :
                a == 2 ? cross_product_3d(e1, e_d) :
                         -cross_product_3d(e_d, e2) - cross_product_3d(e1, e_d);
              dn[j] = sign / length * (P_n * dc);
              // de1 = dc1 - dc0, de2 = dc2 - dc0
              const double n_e = x_s_minus_y * e_d;
              r1 += a == 1 ? n_e : (a == 0 ? -n_e : 0.);
              r2 += a == 2 ? n_e : (a == 0 ? -n_e : 0.);
            }
          if (sliding)
            {
              const double db1 = (m22 * r1 - m12 * r2) / det,
                           db2 = (m11 * r2 - m12 * r1) / det;
              dxi[j]           = db1 * (ref_corner[1] - ref_corner[0]) +
                       db2 * (ref_corner[2] - ref_corner[0]);
            }
          dg[j] = x_s_minus_x_m * dn[j] - n * (dx_m_dxi * dxi[j]);
        }
      // the friction traction's change dt[j] by the same motion
      std::vector<Tensor<1, 3>> dt(friction != nullptr ? 2 * n_dofs : 0);
      if (friction != nullptr)
        for (unsigned int j = 0; j < 2 * n_dofs; ++j)
          dt[j] = friction_traction_change(
            *friction, n, dn[j], -(grad_delta_m * dxi[j]), -eps * dg[j]);
      for (unsigned int i = 0; i < 2 * n_dofs; ++i)
        for (unsigned int j = 0; j < 2 * n_dofs; ++j)
          {
            // dp = -eps dg
            double value = p * (psi[i] * dn[j]) - eps * (n * psi[i]) * dg[j];
            if (friction != nullptr)
              value += psi[i] * dt[j];
            // psi_i = -N_i(xi) e_k on the master: d psi_i = -(grad N_i . dxi)
            if (i >= n_dofs)
              value -=
                T[component[i - n_dofs]] * (master_grad[i - n_dofs] * dxi[j]);
            pair_matrix(i, j) -= factor * value;
          }
    }
  } // namespace



  void
  ParticleContact::setup(const DoFHandler<3>       &dof_handler,
                         const std::vector<double> &penalty_per_particle,
                         const FrictionLaw         &friction_law,
                         const Quadrature<2>       &contact_quadrature)
  {
    this->dof_handler = &dof_handler;
    penalty           = penalty_per_particle;
    friction          = friction_law;
    face_quadrature   = contact_quadrature;
    n_particles       = penalty.size();

    // all surface facets, grouped by particle
    std::vector<std::vector<Facet>> by_particle(n_particles);
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            Facet facet;
            facet.cell        = cell;
            facet.face        = f;
            facet.particle    = cell->material_id();
            unsigned int used = 0;
            for (unsigned int fv = 0; fv < 3; ++fv)
              for (unsigned int v = 0; v < 4; ++v)
                if (cell->vertex_index(v) == cell->face(f)->vertex_index(fv))
                  {
                    facet.local_vertex[fv] = v;
                    used |= (1u << v);
                  }
            for (unsigned int v = 0; v < 4; ++v)
              if ((used & (1u << v)) == 0)
                facet.local_vertex[3] = v;
            by_particle[facet.particle].push_back(facet);
          }
    facets.clear();
    first_facet.assign(1, 0);
    for (const auto &list : by_particle)
      {
        facets.insert(facets.end(), list.begin(), list.end());
        first_facet.push_back(facets.size());
      }
    slave_faces.clear();
    for (unsigned int m = 0; m < facets.size(); ++m)
      if (facets[m].cell->is_locally_owned())
        slave_faces.push_back(m);
    candidate_start.assign(slave_faces.size() + 1, 0);
    candidates.clear();
    couplings.clear();
    pattern_couplings.clear();
    trees.assign(n_particles, FacetTree());

    const std::size_t n_points = slave_faces.size() * face_quadrature.size();
    lambda.assign(n_points, 0.);
    committed_traction.assign(friction.mu > 0 ? n_points : 0, Tensor<1, 3>());
    accumulated_slip.assign(friction.mu > 0 ? n_points : 0, 0.);
    assigned.assign(n_points, numbers::invalid_unsigned_int);
  }



  std::vector<Point<3>>
  ParticleContact::current_vertices(
    const TrilinosWrappers::MPI::Vector &solution) const
  {
    const Triangulation<3> &tria = dof_handler->get_triangulation();
    std::vector<Point<3>>   x(tria.n_vertices());
    std::vector<bool>       done(tria.n_vertices(), false);
    for (const Facet &facet : facets)
      for (unsigned int k = 0; k < 4; ++k)
        {
          const unsigned int v = facet.local_vertex[k];
          const unsigned int i = facet.cell->vertex_index(v);
          if (done[i])
            continue;
          done[i] = true;
          x[i]    = facet.cell->vertex(v);
          for (unsigned int d = 0; d < 3; ++d)
            x[i][d] += solution(facet.cell->vertex_dof_index(v, d));
        }
    return x;
  }



  bool
  ParticleContact::update_search(const TrilinosWrappers::MPI::Vector &solution,
                                 const double                         margin)
  {
    const std::vector<Point<3>> x = current_vertices(solution);
    // facet boxes and particle boxes in the current configuration
    std::vector<BoundingBox<3>> facet_box(facets.size());
    std::vector<BoundingBox<3>> particle_box(n_particles);
    for (unsigned int m = 0; m < facets.size(); ++m)
      {
        const Facet &facet = facets[m];
        Point<3>     lower = x[facet.cell->vertex_index(facet.local_vertex[0])];
        Point<3>     upper = lower;
        for (unsigned int k = 1; k < 3; ++k)
          {
            const Point<3> &c =
              x[facet.cell->vertex_index(facet.local_vertex[k])];
            for (unsigned int d = 0; d < 3; ++d)
              {
                lower[d] = std::min(lower[d], c[d]);
                upper[d] = std::max(upper[d], c[d]);
              }
          }
        facet_box[m] = BoundingBox<3>(std::make_pair(lower, upper));
      }
    for (unsigned int p = 0; p < n_particles; ++p)
      if (first_facet[p + 1] > first_facet[p])
        {
          particle_box[p] = facet_box[first_facet[p]];
          for (unsigned int m = first_facet[p] + 1; m < first_facet[p + 1]; ++m)
            particle_box[p].merge_with(facet_box[m]);
        }

    // broad phase: candidate particle pairs; narrow phase trees for the
    // particles that have a partner. Both search a wider margin, whose cell
    // couplings go into a new matrix pattern when one is needed, so that
    // the pattern lasts while particles move
    const double                      wide = pattern_margin_factor * margin;
    const std::vector<CandidatePair> &pairs =
      broad_search.update(particle_box, wide);
    std::vector<std::vector<unsigned int>> partners(n_particles);
    for (const auto &[a, b] : pairs)
      {
        partners[a].push_back(b);
        partners[b].push_back(a);
      }
    std::vector<bool> built(n_particles, false);
    auto              tree = [&](const unsigned int p) -> const FacetTree              &{
      if (!built[p])
        {
          trees[p].build(
            std::vector<BoundingBox<3>>(facet_box.begin() + first_facet[p],
                                        facet_box.begin() +
                                          first_facet[p + 1]));
          built[p] = true;
        }
      return trees[p];
    };

    candidates.clear();
    candidate_start.assign(1, 0);
    couplings.clear();
    wide_couplings.clear();
    std::vector<unsigned> hits;
    for (const unsigned int s : slave_faces)
      {
        for (const unsigned int b : partners[facets[s].particle])
          {
            hits.clear();
            tree(b).query(facet_box[s], wide, hits);
            for (const unsigned int h : hits)
              {
                const unsigned int                  m = first_facet[b] + h;
                const std::pair<unsigned, unsigned> cells(
                  facets[s].cell->active_cell_index(),
                  facets[m].cell->active_cell_index());
                wide_couplings.push_back(cells);
                if (boxes_overlap(facet_box[s], facet_box[m], margin))
                  {
                    candidates.push_back(m);
                    couplings.push_back(cells);
                  }
              }
          }
        candidate_start.push_back(candidates.size());
      }
    for (auto *list : {&couplings, &wide_couplings})
      {
        std::sort(list->begin(), list->end());
        list->erase(std::unique(list->begin(), list->end()), list->end());
      }
    const bool covered = std::includes(pattern_couplings.begin(),
                                       pattern_couplings.end(),
                                       couplings.begin(),
                                       couplings.end());
    return Utilities::MPI::min(covered ? 1 : 0,
                               dof_handler->get_communicator()) == 1;
  }



  void
  ParticleContact::add_couplings(TrilinosWrappers::SparsityPattern &pattern)
  {
    {
      std::vector<std::pair<unsigned, unsigned>> merged;
      merged.reserve(pattern_couplings.size() + wide_couplings.size());
      std::set_union(pattern_couplings.begin(),
                     pattern_couplings.end(),
                     wide_couplings.begin(),
                     wide_couplings.end(),
                     std::back_inserter(merged));
      pattern_couplings.swap(merged);
    }
    std::vector<DoFHandler<3>::active_cell_iterator> cell_of(
      dof_handler->get_triangulation().n_active_cells());
    for (const Facet &facet : facets)
      cell_of[facet.cell->active_cell_index()] = facet.cell;
    const unsigned int n = dof_handler->get_fe().n_dofs_per_cell();
    std::vector<types::global_dof_index> a(n), b(n);
    for (const auto &[i, j] : pattern_couplings)
      {
        cell_of[i]->get_dof_indices(a);
        cell_of[j]->get_dof_indices(b);
        for (const auto row : a)
          pattern.add_entries(row, b.begin(), b.end());
        for (const auto row : b)
          pattern.add_entries(row, a.begin(), a.end());
      }
  }



  ParticleContact::Projection
  ParticleContact::project(const Point<3>              &x,
                           const unsigned int           m,
                           const std::vector<Point<3>> &vertices,
                           const double                 band,
                           double                      &distance_squared) const
  {
    const Facet            &facet = facets[m];
    std::array<Point<3>, 4> c;
    for (unsigned int k = 0; k < 4; ++k)
      c[k] = vertices[facet.cell->vertex_index(facet.local_vertex[k])];
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
    Tensor<1, 3> n   = cross_product_3d(c[1] - c[0], c[2] - c[0]);
    if (n * (c[3] - c[0]) > 0)
      n = -n;
    result.normal = n / n.norm();
    return result;
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
    const FiniteElement<3>          &fe     = dof_handler->get_fe();
    const unsigned int               n_q    = face_quadrature.size();
    const unsigned int               n_dofs = fe.n_dofs_per_cell();
    FEFaceValues<3>                  fe_face(mapping,
                            fe,
                            face_quadrature,
                            update_values | update_quadrature_points |
                              update_JxW_values);
    std::unique_ptr<FEFaceValues<3>> post_face;
    if (out.post != nullptr)
      post_face =
        std::make_unique<FEFaceValues<3>>(mapping,
                                          out.post->get_fe(),
                                          face_quadrature,
                                          update_values | update_JxW_values);
    const std::vector<Point<3>> x_now = current_vertices(solution);
    std::vector<unsigned int>   component(n_dofs);
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
        fe_face.reinit(slave.cell, slave.face);
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
        if (begin < end)
          {
            fe_face[u].get_function_values(solution, u_values);
            if (friction_on)
              fe_face[u].get_function_values(*committed_solution, u_old);
            slave.cell->get_dof_indices(master_dofs);
            std::copy(master_dofs.begin(),
                      master_dofs.end(),
                      pair_dofs.begin());
          }
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double JxW   = fe_face.JxW(q);
            double       p_out = 0, slip_out = 0, status_out = 0;
            if (begin < end)
              {
                const Point<3> x_s = fe_face.quadrature_point(q) + u_values[q];
                const unsigned int idx = k * n_q + q;
                const unsigned int kept =
                  (out.new_assignment != nullptr || assigned.empty()) ?
                    numbers::invalid_unsigned_int :
                    assigned[idx];
                Projection best;
                double     best_distance = std::numeric_limits<double>::max();
                if (kept != numbers::invalid_unsigned_int)
                  best =
                    project(x_s, kept, x_now, projection_band, best_distance);
                else
                  {
                    // the closest candidate facet
                    for (unsigned int c = begin; c < end; ++c)
                      {
                        double           d2;
                        const Projection pr =
                          project(x_s, candidates[c], x_now, 0., d2);
                        if (d2 < best_distance)
                          {
                            best_distance = d2;
                            best          = pr;
                          }
                      }
                    const unsigned int old = assigned[idx];
                    if (out.new_assignment != nullptr &&
                        old != numbers::invalid_unsigned_int &&
                        old != best.facet)
                      {
                        // hysteresis: keep the old facet while the point
                        // projects into it enlarged by the band, and no
                        // other facet is closer by more than that band
                        double           d2;
                        const Projection pr =
                          project(x_s, old, x_now, projection_band, d2);
                        const double inside =
                          std::min({pr.bary[0], pr.bary[1], pr.bary[2]});
                        double size = 0;
                        for (unsigned int a = 0; a < 3; ++a)
                          size =
                            std::max(size,
                                     (x_now[facets[old].cell->vertex_index(
                                        facets[old].local_vertex[a])] -
                                      x_now[facets[old].cell->vertex_index(
                                        facets[old].local_vertex[(a + 1) % 3])])
                                       .norm());
                        if (inside > -projection_band * (1. - 1e-9) &&
                            std::sqrt(d2) <=
                              std::sqrt(best_distance) + projection_band * size)
                          best = pr;
                      }
                    if (out.new_assignment != nullptr)
                      (*out.new_assignment)[idx] = best.facet;
                  }
                const Facet &master = facets[best.facet];
                // master point and displacement by the master's shape
                // functions at the projection
                Point<3> xi;
                for (unsigned int a = 0; a < 3; ++a)
                  xi +=
                    best.bary[a] * reference_vertices[master.local_vertex[a]];
                master.cell->get_dof_values(solution, master_u);
                Point<3> X_m;
                for (unsigned int a = 0; a < 3; ++a)
                  X_m +=
                    best.bary[a] * master.cell->vertex(master.local_vertex[a]);
                Tensor<1, 3> u_m, u_m_old;
                for (unsigned int i = 0; i < n_dofs; ++i)
                  {
                    master_phi[i] = fe.shape_value(i, xi);
                    u_m[component[i]] += master_u(i) * master_phi[i];
                  }
                if (friction_on)
                  {
                    master.cell->get_dof_values(*committed_solution,
                                                master_old);
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      u_m_old[component[i]] += master_old(i) * master_phi[i];
                  }
                const Tensor<1, 3> &n = best.normal;
                // the normal gap, plus how far the point lies beside the
                // (enlarged) facet: a point beyond the facet's edges, for
                // example in the plane of a neighbour's facet flattened
                // against the same punch, is not in contact with it. Zero for
                // every point that projects into the facet, and continuous
                // in the displacement (doc/theory.md section 9)
                const Tensor<1, 3> off =
                  x_s -
                  (best.bary[0] *
                     x_now[master.cell->vertex_index(master.local_vertex[0])] +
                   best.bary[1] *
                     x_now[master.cell->vertex_index(master.local_vertex[1])] +
                   best.bary[2] *
                     x_now[master.cell->vertex_index(master.local_vertex[2])]);
                const double g =
                  (x_s - (X_m + u_m)) * n + (off - (off * n) * n).norm();
                const double eps =
                  std::min(penalty[slave.particle], penalty[master.particle]);
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
                    (*out.new_lambda)[idx] = p;
                    // d(p^2 / 2 eps) / d lambda times the multiplier's
                    // change per unit relaxation
                    result.multiplier_work +=
                      weight * p / eps * (p - lambda[idx]) * JxW;
                  }
                if (out.new_traction != nullptr && friction_on)
                  {
                    (*out.new_traction)[idx] = r.traction;
                    const Tensor<1, 3> slip  = delta - (delta * n) * n;
                    if (r.status == ContactStatus::slip)
                      (*out.new_slip)[idx] += slip.norm();
                    // the traction t = -eps_t s_e opposes the slip beyond
                    // the spring's elastic slip s_e (the arctangent law has
                    // no spring: all slip work is dissipated)
                    result.friction_work -=
                      weight *
                      (r.traction *
                       (friction.model == FrictionModel::coulomb ?
                          Tensor<1, 3>(slip +
                                       (r.traction - committed_traction[idx]) /
                                         (friction.tangential_ratio * eps)) :
                          slip)) *
                      JxW;
                  }
                result.max_penetration = std::max(result.max_penetration, -g);
                const bool predicted =
                  (p <= 0. && out.matrix != nullptr && g < out.tangent_margin);
                if (p > 0. || predicted)
                  {
                    // relative shape functions: slave phi, minus master phi
                    master.cell->get_dof_indices(master_dofs);
                    std::copy(master_dofs.begin(),
                              master_dofs.end(),
                              pair_dofs.begin() + n_dofs);
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      {
                        psi[i]                        = fe_face[u].value(i, q);
                        psi[n_dofs + i]               = Tensor<1, 3>();
                        psi[n_dofs + i][component[i]] = -master_phi[i];
                      }
                    if (p > 0.)
                      {
                        ++result.n_active;
                        if (friction_on && r.status == ContactStatus::slip)
                          ++result.n_slip;
                        result.normal_force += weight * p * JxW;
                        // the potential p^2 / 2 eps of p = max(0, lambda -
                        // eps g) and the stick spring's
                        result.elastic_energy +=
                          weight * 0.5 *
                          (p * p + (friction_on && friction.model ==
                                                     FrictionModel::coulomb ?
                                      r.traction.norm_square() /
                                        friction.tangential_ratio :
                                      0.)) /
                          eps * JxW;
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
        if (post_face)
          add_surface_field_values(post_indices,
                                   post_p,
                                   post_slip,
                                   post_status,
                                   post_weights,
                                   *out.sums);
      }

    result.normal_force    = Utilities::MPI::sum(result.normal_force, comm);
    result.friction_force  = Utilities::MPI::sum(result.friction_force, comm);
    result.max_penetration = Utilities::MPI::max(result.max_penetration, comm);
    result.friction_work   = Utilities::MPI::sum(result.friction_work, comm);
    result.elastic_energy  = Utilities::MPI::sum(result.elastic_energy, comm);
    result.multiplier_work = Utilities::MPI::sum(result.multiplier_work, comm);
    result.n_active        = Utilities::MPI::sum(result.n_active, comm);
    result.n_slip          = Utilities::MPI::sum(result.n_slip, comm);
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
    unsigned int              n_changed = 0;
    Outputs                   out;
    out.new_assignment = &new_assignment;
    out.n_changed      = &n_changed;
    loop(mapping, solution, out);
    assigned.swap(new_assignment);
    return Utilities::MPI::sum(n_changed, dof_handler->get_communicator());
  }



  std::vector<unsigned int>
  ParticleContact::contact_partners(
    const Mapping<3>                    &mapping,
    const TrilinosWrappers::MPI::Vector &solution) const
  {
    std::set<std::pair<unsigned, unsigned>> pairs;
    Outputs                                 out;
    out.pairs = &pairs;
    loop(mapping, solution, out);
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
