// Homogeneous uniaxial compression of a small tetrahedral block to 50 % true
// strain through finite-element assembly (not only the material point): P1
// tetrahedra, symmetry planes x = 0, y = 0, z = 0, the top z = 1 pushed down,
// lateral faces free, Newton on the assembled residual with the J2 law of
// Densify. The axial force and the volume are compared with the exact
// Hencky/J2 result for no hardening and for linear hardening. Then the top
// goes back until the force is zero: the height after unloading against the
// elastic recovery of the Hencky law (springback).
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>

#include <densify/material/j2_plasticity.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>

using namespace densify;

namespace
{
  bool all_ok = true;

  /// Exact axial Kirchhoff stress magnitude at log strain magnitude @p e.
  double
  exact_tau(const J2Parameters &p, const double e)
  {
    if (p.E * e <= p.sigma0)
      return p.E * e;
    if (p.hardening == Hardening::linear)
      return (p.sigma0 + p.H * e) / (1. + p.H / p.E);
    return p.sigma0;
  }

  void
  run(const J2Parameters &parameters)
  {
    const J2Plasticity material(parameters);
    std::cout << material.name() << std::endl;
    const double kappa = parameters.E / (3. * (1. - 2. * parameters.nu));

    Triangulation<3> tria;
    GridGenerator::subdivided_hyper_rectangle_with_simplices(tria,
                                                             {2, 2, 2},
                                                             Point<3>(0, 0, 0),
                                                             Point<3>(1, 1, 1));
    const FESystem<3>  fe(FE_SimplexP<3>(1), 3);
    const MappingFE<3> mapping(FE_SimplexP<3>(1));
    DoFHandler<3>      dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    const unsigned int n_dofs = dof_handler.n_dofs();

    // symmetry planes and the pushed top: constrained DoF -> its face
    std::map<types::global_dof_index, bool> constrained; // true: top
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int d = 0; d < 3; ++d)
          {
            const double x = cell->vertex(v)[d];
            if (std::abs(x) < 1e-12)
              constrained[cell->vertex_dof_index(v, d)] = false;
            else if (d == 2 && std::abs(x - 1.) < 1e-12)
              constrained[cell->vertex_dof_index(v, d)] = true;
          }

    const QGaussSimplex<3> quadrature(2);
    FEValues<3>            fe_values(mapping,
                          fe,
                          quadrature,
                          update_gradients | update_JxW_values);
    const unsigned int     n = fe.n_dofs_per_cell(), n_q = quadrature.size();
    std::vector<MaterialState> committed(tria.n_active_cells() * n_q),
      trial(committed.size());
    Vector<double>                       u(n_dofs), R(n_dofs), du(n_dofs);
    FullMatrix<double>                   K(n_dofs, n_dofs);
    std::vector<types::global_dof_index> dofs(n);
    Tensor<2, 3>                         P;
    Tensor<4, 3>                         A;
    double                               volume = 0.;

    // residual, tangent and current volume at u
    const auto assemble = [&]() {
      R      = 0;
      K      = 0;
      volume = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int q = 0; q < n_q; ++q)
            {
              Tensor<2, 3> F = unit_symmetric_tensor<3>();
              for (unsigned int i = 0; i < n; ++i)
                F[fe.system_to_component_index(i).first] +=
                  u(dofs[i]) * fe_values.shape_grad(i, q);
              const unsigned int k = cell->active_cell_index() * n_q + q;
              material.evaluate(F, &committed[k], &trial[k], P, A);
              const double JxW = fe_values.JxW(q);
              volume += determinant(F) * JxW;
              for (unsigned int i = 0; i < n; ++i)
                {
                  const unsigned int ci = fe.system_to_component_index(i).first;
                  const Tensor<1, 3> gi = fe_values.shape_grad(i, q);
                  R(dofs[i]) += (P[ci] * gi) * JxW;
                  for (unsigned int j = 0; j < n; ++j)
                    {
                      const unsigned int cj =
                        fe.system_to_component_index(j).first;
                      const Tensor<1, 3> gj = fe_values.shape_grad(j, q);
                      double             v  = 0;
                      for (unsigned int J = 0; J < 3; ++J)
                        for (unsigned int L = 0; L < 3; ++L)
                          v += A[ci][J][cj][L] * gi[J] * gj[L];
                      K(dofs[i], dofs[j]) += v * JxW;
                    }
                }
            }
        }
    };

    // equilibrium with the top at @p stretch from the committed state: the
    // axial force; the Newton iterations in @p it
    const auto equilibrate = [&](const double stretch, unsigned int &it) {
      for (const auto &[i, top] : constrained)
        u(i) = top ? stretch - 1. : 0.;
      double force = 0.;
      for (it = 0;; ++it)
        {
          assemble();
          force = 0;
          for (const auto &[i, top] : constrained)
            if (top)
              force -= R(i);
          double r2 = 0;
          for (unsigned int i = 0; i < n_dofs; ++i)
            if (constrained.count(i) == 0)
              r2 += R(i) * R(i);
          if (std::sqrt(r2) < 1e-10 * parameters.sigma0 || it == 20)
            break;
          // constrained rows and columns -> identity, zero right-hand side
          for (const auto &[i, top] : constrained)
            {
              for (unsigned int j = 0; j < n_dofs; ++j)
                K(i, j) = K(j, i) = 0.;
              K(i, i) = 1.;
              R(i)    = 0.;
            }
          K.gauss_jordan();
          K.vmult(du, R);
          u -= du;
        }
      return force;
    };

    const unsigned int n_steps         = 50;
    const double       e_end           = 0.5;
    double             max_force_error = 0., max_volume_error = 0.;
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        const double e       = e_end * step / n_steps;
        const double stretch = std::exp(-e);
        unsigned int it      = 0;
        const double force   = equilibrate(stretch, it);
        committed            = trial;

        // exact: uniaxial Kirchhoff stress tau, force tau * A0 / stretch
        // (Cauchy tau / J on the current area J A0 / stretch), volume
        // J = exp(-tau / (3 kappa))
        const double tau          = exact_tau(parameters, e);
        const double exact_force  = tau / stretch;
        const double exact_volume = std::exp(-tau / (3. * kappa));
        max_force_error =
          std::max(max_force_error, std::abs(force / exact_force - 1.));
        max_volume_error =
          std::max(max_volume_error,
                   std::abs((volume - 1.) / (exact_volume - 1.) - 1.));
        if (step % 10 == 0)
          std::cout << "  true strain " << e << ": force "
                    << std::setprecision(6) << force << " N (exact "
                    << exact_force << "), volume change " << volume - 1.
                    << " (exact " << exact_volume - 1. << "), newton " << it
                    << std::endl;
      }
    bool ok = max_force_error < 5e-3 && max_volume_error < 5e-3;

    // unloading from the largest strain: the top where the force returns to
    // zero (secant), against the elastic recovery of the Hencky law, whose
    // uniaxial log strain recovers by tau / E (tau the Kirchhoff stress at
    // the largest strain): stretch exp(-e_end + tau / E), volume back to 1
    {
      const double tau        = exact_tau(parameters, e_end);
      const double loaded     = std::exp(-e_end);
      const double exact      = std::exp(-e_end + tau / parameters.E);
      double       s0         = loaded;
      double       s1         = loaded * (1 + 0.5 * tau / parameters.E);
      unsigned int it         = 0;
      double       f0         = equilibrate(s0, it);
      double       f1         = equilibrate(s1, it);
      unsigned int iterations = 0;
      for (; std::abs(f1) > 1e-10 * parameters.sigma0 && iterations < 20;
           ++iterations)
        {
          const double s2 = s1 - f1 * (s1 - s0) / (f1 - f0);
          s0              = s1;
          f0              = f1;
          s1              = s2;
          f1              = equilibrate(s1, it);
        }
      const double recovery_error =
        std::abs((s1 - loaded) / (exact - loaded) - 1.);
      const bool unloaded_ok =
        recovery_error < 0.02 && std::abs(volume - 1.) < 1e-6 * tau / kappa;
      // round-off quantities only as bounds (the output is compared)
      std::cout << "  unloaded (force below 1e-10 sigma0: "
                << (std::abs(f1) <= 1e-10 * parameters.sigma0 ? "yes" : "no")
                << ") at height " << std::setprecision(6) << s1 << " (exact "
                << exact << ", loaded " << loaded
                << "); elastic recovery within 1e-6 of exact: "
                << (recovery_error < 1e-6 ? "yes" : "no")
                << ", volume back to 1: "
                << (std::abs(volume - 1.) < 1e-6 * tau / kappa ? "yes" : "no")
                << std::endl;
      std::cout
        << "  height after unloading within 2 % of the elastic recovery: "
        << (unloaded_ok ? "yes" : "no") << std::endl;
      ok = ok && unloaded_ok;
    }
    all_ok = all_ok && ok;
    std::cout << "  largest relative error: force " << std::scientific
              << std::setprecision(1) << max_force_error << ", volume change "
              << max_volume_error << std::defaultfloat << std::endl;
    std::cout << "  force and volume change within 0.5 % of exact: "
              << (ok ? "yes" : "no") << std::endl;
  }
} // namespace



int
main()
{
  J2Parameters p = material_preset("Sn");
  run(p);
  p.hardening = Hardening::linear;
  p.H         = 500.;
  p.label     = "Sn, H = 500 MPa";
  run(p);
  return all_ok ? 0 : 1;
}
