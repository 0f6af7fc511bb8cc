// The contact law's stiffness against central finite differences of the
// traction, for Coulomb stick, Coulomb slip and the arctangent law, with the
// consistent tangent; the symmetric tangent is symmetric; and the secant
// start adds the symmetric tangent's stiffness along the slip of Coulomb slip
// to the consistent tangent, where that has none, and nothing else; the
// consistent tangent without its pressure coupling is symmetric and differs
// from the consistent one by that coupling, (eps / p) t n^T, only.
#include <densify/contact/contact_law.h>

#include "test_utilities.h"

#include <iomanip>
#include <iostream>

int
main()
{
  using namespace densify;
  Tensor<1, 3> n({0.2, -0.3, 1.});
  n /= n.norm();
  const Tensor<1, 3> t_old0({0.3, -0.2, 0.06});
  const double       eps = 1e3, lambda = 0.5, g0 = -1e-3;
  const char        *names[] = {"open", "stick", "slip"};
  for (const std::string model : {"Coulomb", "arctangent"})
    for (const double slip : {1e-6, 1e-3})
      for (const double history : {0.01, 1.})
        {
          const Tensor<1, 3> t_old = history * t_old0;
          FrictionLaw        law;
          law.mu             = 0.2;
          law.slip           = slip_rule(model);
          law.regularisation = 1e-4;
          law.consistent     = true;
          const Tensor<1, 3> d0({0.7 * slip, 0.4 * slip, -0.1 * slip});
          // the traction -(p n + t) as a function of the relative displacement
          auto f = [&](const Tensor<1, 3> &d) {
            const ContactResponse r = evaluate_contact_law(
              lambda, g0 + n * d, eps, n, t_old, d, eps, law);
            return Tensor<1, 3>(-(r.pressure * n + r.traction));
          };
          const ContactResponse r0 = evaluate_contact_law(
            lambda, g0 + n * d0, eps, n, t_old, d0, eps, law);
          double error = 0;
          for (unsigned int j = 0; j < 3; ++j)
            {
              Tensor<1, 3> e;
              e[j]                  = 1e-7 * slip;
              const Tensor<1, 3> fd = (f(d0 + e) - f(d0 - e)) / (2 * e[j]);
              for (unsigned int i = 0; i < 3; ++i)
                error = std::max(error, std::abs(fd[i] - r0.stiffness[i][j]));
            }
          error /= r0.stiffness.norm();
          // the default (secant) tangent is symmetric
          law.consistent = false;
          const Tensor<2, 3> K =
            evaluate_contact_law(
              lambda, g0 + n * d0, eps, n, t_old, d0, eps, law)
              .stiffness;
          const double asymmetry = (K - transpose(K)).norm() / K.norm();
          // the secant start (FrictionLaw::slip_secant): the consistent
          // tangent plus, along the slip of Coulomb slip, the secant
          // stiffness of the symmetric tangent (where the exact one has
          // none); the same traction
          law.consistent           = true;
          law.slip_secant          = true;
          const ContactResponse rs = evaluate_contact_law(
            lambda, g0 + n * d0, eps, n, t_old, d0, eps, law);
          Tensor<2, 3> expected = r0.stiffness;
          if (model == "Coulomb" && r0.status == ContactStatus::slip)
            {
              const Tensor<1, 3> t_hat = r0.traction / r0.traction.norm();
              expected += (t_hat * K * t_hat) * outer_product(t_hat, t_hat);
            }
          const bool secant_start =
            (rs.traction - r0.traction).norm() == 0. &&
            rs.pressure == r0.pressure &&
            (rs.stiffness - expected).norm() <= 1e-14 * K.norm();
          // without the pressure coupling (symmetric-secant-start once
          // the secant start has ended)
          law.slip_secant          = false;
          law.pressure_coupling    = false;
          const ContactResponse ru = evaluate_contact_law(
            lambda, g0 + n * d0, eps, n, t_old, d0, eps, law);
          const Tensor<2, 3> coupling =
            r0.status == ContactStatus::slip ?
              Tensor<2, 3>(eps / r0.pressure * outer_product(r0.traction, n)) :
              Tensor<2, 3>();
          const bool uncoupled =
            (ru.traction - r0.traction).norm() == 0. &&
            (ru.stiffness + coupling - r0.stiffness).norm() <=
              1e-14 * K.norm() &&
            (ru.stiffness - transpose(ru.stiffness)).norm() <=
              1e-14 * ru.stiffness.norm();
          std::cout << (model == "Coulomb" ? "Coulomb   " : "arctangent")
                    << " slip " << std::setw(5) << slip << " history "
                    << std::setw(4) << history << " "
                    << names[static_cast<int>(r0.status)]
                    << ": consistent tangent vs FD "
                    << testing::yes(error < 1e-6)
                    << ", symmetric tangent symmetric "
                    << testing::yes(asymmetry < 1e-14)
                    << ", secant start as expected "
                    << testing::yes(secant_start) << ", uncoupled symmetric "
                    << testing::yes(uncoupled) << std::endl;
        }
  return testing::all_passed ? 0 : 1;
}
