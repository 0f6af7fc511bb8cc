// A friction law added from outside Densify's sources, through the
// extension point of doc/architecture.md ("A friction law"): a class derived
// from SlipRule, registered under a name of its own, then chosen by
// Contact/Friction model like the built-in laws. The toy law is a
// regularised rigid-plastic Coulomb law without a stick state,
// t = -mu p s / sqrt(|s|^2 + delta^2) with a fixed delta, so |t| < mu p for
// every slip s.
// 1. At one point: the contact law's stiffness with the toy's traction
//    equals central differences (with the pressure coupling of the
//    consistent tangent), and the point stores no spring energy.
// 2. Through the whole program (the sphere of friction_sliding, pressed
//    between two punches and pulled sideways by a body force with
//    b V / 2 = x mu N): at x = 0.97 the punches hold the pull, each below
//    its limit mu N; at x = 1.01 no equilibrium exists and the run stops.
#include <deal.II/base/mpi.h>
#include <deal.II/base/symmetric_tensor.h>

#include <densify/contact/contact_law.h>
#include <densify/simulator.h>

#include "test_utilities.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
  using namespace densify;

  /// t = -mu p s / q, q = sqrt(|s|^2 + delta^2).
  class ToySlip : public SlipRule
  {
  public:
    explicit ToySlip(const double delta)
      : delta(delta)
    {}

    std::string
    name() const override
    {
      return "toy";
    }

    bool
    respond(const FrictionLaw & /*law*/,
            const Tensor<2, 3> &P,
            const Tensor<1, 3> &s,
            const Tensor<1, 3> & /*committed_traction*/,
            const double /*eps_t*/,
            const double     limit,
            ContactResponse &r) const override
    {
      const double q = std::sqrt(s * s + delta * delta);
      r.traction     = -limit / q * s;
      // -dt/dd with s = P d
      r.stiffness += limit * (P / q - outer_product(s, s) / (q * q * q));
      return true;
    }

    void
    derivatives(const FrictionLaw     &law,
                const ContactResponse &r,
                const Tensor<2, 3> & /*P*/,
                const Tensor<1, 3> &s,
                const Tensor<1, 3> & /*committed_traction*/,
                const double /*eps_t*/,
                FrictionTerms &terms) const override
    {
      const double       q = std::sqrt(s * s + delta * delta);
      const Tensor<2, 3> I = unit_symmetric_tensor<3>();
      terms.dt_ds =
        -law.mu * r.pressure * (I / q - outer_product(s, s) / (q * q * q));
    }

    bool
    has_stick_spring() const override
    {
      return false;
    }

  private:
    const double delta;
  };



  /// The contact law with the toy rule at one point against central
  /// differences; its energy and dissipating slip.
  void
  check_point(std::ostream &out)
  {
    Tensor<1, 3> n({0.2, -0.3, 1.});
    n /= n.norm();
    const double eps = 1e3, lambda = 0.5, g0 = -1e-3;
    FrictionLaw  law;
    law.mu         = 0.2;
    law.slip       = slip_rule("toy");
    law.consistent = true;
    const Tensor<1, 3> t_old({0.03, -0.02, 0.006});
    double             worst = 0;
    for (const double slip : {1e-6, 1e-4, 1e-2})
      {
        const Tensor<1, 3> d0({0.7 * slip, 0.4 * slip, -0.1 * slip});
        const auto         f = [&](const Tensor<1, 3> &d) {
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
        worst = std::max(worst, error / r0.stiffness.norm());
      }
    const Tensor<1, 3>    d({1e-3, 0., 0.});
    const ContactResponse r =
      evaluate_contact_law(lambda, g0 + n * d, eps, n, t_old, d, eps, law);
    const Tensor<1, 3> s = d - (d * n) * n;
    const bool         no_spring =
      law.elastic_energy(r, eps, true) == 0.5 * r.pressure * r.pressure / eps &&
      (law.dissipating_slip(s, r.traction, t_old, eps) - s).norm() == 0.;
    out << "toy law at a point: tangent vs central differences "
        << testing::yes(worst < 1e-6) << ", below the Coulomb limit "
        << testing::yes(r.traction.norm() < law.mu * r.pressure)
        << ", no spring energy " << testing::yes(no_spring) << std::endl;
  }



  /// The sphere of friction_sliding with the toy law, pulled by @p b.
  std::unique_ptr<Simulator>
  make(Parameters &parameters, ParameterHandler &prm, const double b)
  {
    testing::read_scene(
      parameters,
      prm,
      "hertz.prm",
      testing::pulled_sphere("output_b" + std::to_string(b),
                             b,
                             {"Contact/Friction model=toy",
                              "Contact/Friction tangent=consistent",
                              "Solver/Linear solver=gmres-amg"}));
    return std::make_unique<Simulator>(parameters, MPI_COMM_WORLD, false);
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool   root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  const double mu   = 0.2;
  register_slip_rule(std::make_shared<ToySlip>(1e-4));
  std::ostringstream out;
  check_point(out);
  out << "Contact/Friction model offers the toy law: "
      << testing::yes(slip_rule_names() == "Coulomb|arctangent|toy")
      << std::endl;

  // the normal force and the volume, without the pull
  double N = 0, V = 0;
  {
    Parameters       parameters;
    ParameterHandler prm;
    auto             simulator = make(parameters, prm, 0.);
    simulator->setup();
    for (const double v : simulator->particle_volumes())
      V += v;
    simulator->run();
    N = simulator->statistics().back().lower_punch_force;
  }

  // below the limit: held, each punch below mu N
  {
    const double     b = 2 * 0.97 * mu * N / V;
    Parameters       parameters;
    ParameterHandler prm;
    auto             simulator = make(parameters, prm, b);
    simulator->run();
    const StepStatistics &s = simulator->statistics().back();
    const double total      = s.lower_punch_friction + s.upper_punch_friction;
    out << "b V / 2 = 0.97 mu N: friction of the punches / (b V) = "
        << std::setprecision(4) << total / (b * V) << " (1 to 1e-3: "
        << testing::yes(total / (b * V) > 1 - 1e-9 &&
                        total / (b * V) < 1 + 1e-3)
        << "), both punches below mu N: "
        << testing::yes(s.lower_punch_friction < mu * s.lower_punch_force &&
                        s.upper_punch_friction < mu * s.upper_punch_force)
        << std::endl;
  }

  // above the limit: slides, so no static equilibrium
  {
    const double     b = 2 * 1.01 * mu * N / V;
    Parameters       parameters;
    ParameterHandler prm;
    auto             simulator = make(parameters, prm, b);
    bool             failed    = false;
    try
      {
        simulator->run();
      }
    catch (const std::exception &)
      {
        failed = true;
      }
    out << "b V / 2 = 1.01 mu N: slides (no equilibrium, the run stops): "
        << testing::yes(failed) << std::endl;
  }
  if (root)
    std::cout << out.str();
  return testing::all_passed ? 0 : 1;
}
