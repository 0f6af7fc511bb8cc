// The slave faces' quadrature data in the reference configuration.
#include <deal.II/fe/fe_values.h>

#include <densify/contact/face_tables.h>

namespace densify
{
  void
  FaceTables::reinit(
    const Mapping<3>       &mapping,
    const FiniteElement<3> &fe,
    const Quadrature<2>    &quadrature,
    const std::vector<
      std::pair<DoFHandler<3>::active_cell_iterator, unsigned int>> &faces)
  {
    n_q    = quadrature.size();
    n_dofs = fe.n_dofs_per_cell();
    components.resize(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      components[i] = fe.system_to_component_index(i).first;
    FEFaceValues<3> fe_face(mapping,
                            fe,
                            quadrature,
                            update_values | update_quadrature_points |
                              update_JxW_values);
    points.resize(faces.size() * n_q);
    weights.resize(faces.size() * n_q);
    dof_indices.resize(faces.size() * n_dofs);
    table_of.resize(faces.size());
    tables.clear();
    std::vector<types::global_dof_index> cell_dofs(n_dofs);
    std::vector<double>                  table(n_dofs * n_q);
    for (unsigned int k = 0; k < faces.size(); ++k)
      {
        const auto &[cell, f] = faces[k];
        fe_face.reinit(cell, f);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            points[k * n_q + q]  = fe_face.quadrature_point(q);
            weights[k * n_q + q] = fe_face.JxW(q);
          }
        cell->get_dof_indices(cell_dofs);
        std::copy(cell_dofs.begin(),
                  cell_dofs.end(),
                  dof_indices.begin() + k * n_dofs);
        for (unsigned int i = 0; i < n_dofs; ++i)
          for (unsigned int q = 0; q < n_q; ++q)
            table[i * n_q + q] =
              fe_face.shape_value_component(i, q, components[i]);
        // the same values as an earlier face (same reference face and
        // orientation) share its table
        unsigned int t = 0;
        while (t < tables.size() && tables[t] != table)
          ++t;
        if (t == tables.size())
          tables.push_back(table);
        table_of[k] = t;
      }
    made = true;
  }



  void
  FaceTables::values(const unsigned int         k,
                     const AllValues           &values,
                     std::vector<Tensor<1, 3>> &u) const
  {
    const types::global_dof_index *dofs  = &dof_indices[k * n_dofs];
    const double                  *table = tables[table_of[k]].data();
    for (unsigned int q = 0; q < n_q; ++q)
      u[q] = Tensor<1, 3>();
    for (unsigned int i = 0; i < n_dofs; ++i)
      {
        const double value = values[dofs[i]];
        if (value == 0.)
          continue;
        const double *shape = table + i * n_q;
        for (unsigned int q = 0; q < n_q; ++q)
          u[q][components[i]] += value * shape[q];
      }
  }
} // namespace densify
