// Augmented-Lagrangian contact between the surfaces of deformable
// particles: the set-up, the candidate search and the couplings of the
// matrix (the forces are in particle_contact.cc).
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <densify/contact/closest_point.h>
#include <densify/contact/particle_contact.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <limits>

namespace densify
{
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
            for (unsigned int k = 0; k < 4; ++k)
              facet.vertex[k] = cell->vertex_index(facet.local_vertex[k]);
            for (unsigned int k = 0; k < 3; ++k)
              facet.position[k] = cell->vertex(facet.local_vertex[k]);
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
    const unsigned int n_dofs = dof_handler.get_fe().n_dofs_per_cell();
    facet_dofs.resize(facets.size() * n_dofs);
    surface_vertices.clear();
    std::vector<bool> done(dof_handler.get_triangulation().n_vertices(), false);
    std::vector<types::global_dof_index> cell_dofs(n_dofs);
    for (unsigned int m = 0; m < facets.size(); ++m)
      {
        const Facet &facet = facets[m];
        facet.cell->get_dof_indices(cell_dofs);
        std::copy(cell_dofs.begin(),
                  cell_dofs.end(),
                  facet_dofs.begin() + m * n_dofs);
        for (unsigned int k = 0; k < 4; ++k)
          {
            const unsigned int v = facet.local_vertex[k];
            const unsigned int i = facet.cell->vertex_index(v);
            if (done[i])
              continue;
            done[i] = true;
            SurfaceVertex vertex;
            vertex.index    = i;
            vertex.position = facet.cell->vertex(v);
            for (unsigned int d = 0; d < 3; ++d)
              vertex.dofs[d] = facet.cell->vertex_dof_index(v, d);
            surface_vertices.push_back(vertex);
          }
      }
    tables = FaceTables();
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
    assigned_in_band.assign(n_points, 1);
    near.valid = false;
  }



  std::vector<Point<3>>
  ParticleContact::current_vertices(
    const TrilinosWrappers::MPI::Vector &solution) const
  {
    std::vector<Point<3>> x(dof_handler->get_triangulation().n_vertices());
    for (const SurfaceVertex &vertex : surface_vertices)
      {
        Point<3> &y = x[vertex.index];
        y           = vertex.position;
        for (unsigned int d = 0; d < 3; ++d)
          y[d] += solution(vertex.dofs[d]);
      }
    return x;
  }



  const std::vector<Point<3>> &
  ParticleContact::current_vertices(const AllValues &values) const
  {
    std::vector<Point<3>> &x = vertex_buffer;
    x.resize(dof_handler->get_triangulation().n_vertices());
    for (const SurfaceVertex &vertex : surface_vertices)
      {
        Point<3> &y = x[vertex.index];
        y           = vertex.position;
        for (unsigned int d = 0; d < 3; ++d)
          y[d] += values[vertex.dofs[d]];
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
    near.valid         = false;
    near.reach         = margin;
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



  void
  ParticleContact::update_near_lists(const std::vector<Point<3>> &x_now,
                                     const AllValues             &values) const
  {
    // still valid while 4 max |x - x_ref| < reach (with a tenth to spare
    // against round-off in the distances)
    if (near.valid)
      {
        double moved2 = 0.;
        for (unsigned int j = 0; j < surface_vertices.size(); ++j)
          moved2 =
            std::max(moved2,
                     (x_now[surface_vertices[j].index] - near.reference[j])
                       .norm_square());
        if (16. * moved2 < 0.81 * near.reach * near.reach)
          return;
      }
    const unsigned int n_q      = face_quadrature.size();
    const unsigned int n_points = slave_faces.size() * n_q;
    if (!near.corners_checked)
      {
        // is every slave point a corner of its facet (its reference position
        // the vertex's)?
        near.corners_checked = true;
        near.at_corners      = true;
        near.point_vertex.assign(n_points, numbers::invalid_unsigned_int);
        for (unsigned int k = 0; k < slave_faces.size(); ++k)
          {
            const Facet &f    = facets[slave_faces[k]];
            const double size = (f.position[1] - f.position[0]).norm();
            for (unsigned int q = 0; q < n_q; ++q)
              {
                unsigned int &vertex = near.point_vertex[k * n_q + q];
                for (unsigned int a = 0; a < 3; ++a)
                  if ((tables.point(k, q) - f.position[a]).norm() <=
                      1e-12 * size)
                    vertex = f.vertex[a];
                near.at_corners =
                  near.at_corners && vertex != numbers::invalid_unsigned_int;
              }
          }
      }
    const bool by_vertex = near.by_vertex && near.at_corners;
    // by vertex: the slave points with candidates ordered by their vertex,
    // then by index; each vertex's run is evaluated at its first point
    std::vector<std::pair<unsigned int, unsigned int>> order;
    std::vector<std::pair<unsigned int, unsigned int>> run;
    if (by_vertex)
      {
        for (unsigned int k = 0; k < slave_faces.size(); ++k)
          if (candidate_start[k] < candidate_start[k + 1])
            for (unsigned int q = 0; q < n_q; ++q)
              order.emplace_back(near.point_vertex[k * n_q + q], k * n_q + q);
        std::sort(order.begin(), order.end());
        run.assign(n_points, {0, 0});
        for (unsigned int a = 0, b = 0; a < order.size(); a = b)
          {
            while (b < order.size() && order[b].first == order[a].first)
              ++b;
            run[order[a].second] = {a, b};
          }
      }

    std::vector<Tensor<1, 3>>                    u_values(n_q);
    std::vector<unsigned int>                    merged;
    std::vector<double>                          distance;
    std::vector<std::pair<unsigned int, double>> closest;
    near.start.assign(1, 0);
    near.facets.clear();
    near.copy_start.assign(1, 0);
    near.copies.clear();
    near.weight.assign(by_vertex ? n_points : 0, 0.);
    for (unsigned int k = 0; k < slave_faces.size(); ++k)
      {
        const unsigned int begin = candidate_start[k],
                           end   = candidate_start[k + 1];
        if (begin < end)
          tables.values(k, values, u_values);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const unsigned int  idx   = k * n_q + q;
            const unsigned int *first = candidates.data() + begin,
                               *last  = candidates.data() + end;
            if (by_vertex && begin < end)
              {
                // the copies and the union of their faces' candidates
                for (unsigned int c = run[idx].first; c < run[idx].second; ++c)
                  {
                    const unsigned int copy = order[c].second;
                    near.copies.push_back(copy);
                    near.weight[idx] += tables.JxW(copy / n_q, copy % n_q);
                  }
                if (run[idx].second > run[idx].first + 1)
                  {
                    merged.clear();
                    for (unsigned int c = run[idx].first; c < run[idx].second;
                         ++c)
                      {
                        const unsigned int face = order[c].second / n_q;
                        merged.insert(merged.end(),
                                      candidates.data() + candidate_start[face],
                                      candidates.data() +
                                        candidate_start[face + 1]);
                      }
                    std::sort(merged.begin(), merged.end());
                    merged.erase(std::unique(merged.begin(), merged.end()),
                                 merged.end());
                    first = merged.data();
                    last  = merged.data() + merged.size();
                  }
                else if (run[idx].second == run[idx].first)
                  last = first; // a copy of a vertex evaluated elsewhere
              }
            if (first < last)
              {
                const Point<3> x_s = tables.point(k, q) + u_values[q];
                // per master particle the facets within the reach of its
                // closest one (choose_facet() takes each particle's closest)
                distance.resize(last - first);
                closest.clear();
                for (const unsigned int *c = first; c != last; ++c)
                  {
                    double d2;
                    project(x_s, *c, x_now, 0., d2, false);
                    distance[c - first]  = std::sqrt(d2);
                    const unsigned int p = facets[*c].particle;
                    auto               o = closest.begin();
                    while (o != closest.end() && o->first != p)
                      ++o;
                    if (o == closest.end())
                      closest.emplace_back(p, distance[c - first]);
                    else
                      o->second = std::min(o->second, distance[c - first]);
                  }
                for (const unsigned int *c = first; c != last; ++c)
                  {
                    const unsigned int p = facets[*c].particle;
                    auto               o = closest.begin();
                    while (o->first != p)
                      ++o;
                    if (distance[c - first] <= o->second + near.reach)
                      near.facets.push_back(*c);
                  }
              }
            near.start.push_back(near.facets.size());
            near.copy_start.push_back(near.copies.size());
          }
      }
    near.reference.resize(surface_vertices.size());
    for (unsigned int j = 0; j < surface_vertices.size(); ++j)
      near.reference[j] = x_now[surface_vertices[j].index];
    near.valid = true;
    ++near.builds;
  }
} // namespace densify
