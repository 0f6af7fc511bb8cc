// Central-difference explicit dynamics over a system of forces: the
// integrator, its time map and its energy account.
#include <deal.II/base/mpi.h>

#include <densify/drivers/explicit_dynamics.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace densify
{
  ExplicitDynamics::ExplicitDynamics(const ExplicitParameters &prm,
                                     const double              scene_end_time,
                                     const MPI_Comm            comm)
    : prm(prm)
    , scene_end(scene_end_time)
    , comm(comm)
    , step_profile(parse_table(prm.step_profile, "Explicit/Step profile"))
  {}



  std::string
  ExplicitDynamics::remedy() const
  {
    std::ostringstream text;
    if (scaled)
      // the mass scaling holds the step at Loading time / Number of steps
      // and adds the mass the safety asks for: a lower safety only adds
      // mass, and inertia with it
      text << "raise Explicit/Number of steps (now " << prm.n_steps
           << "; the mass scaling sets the step, and a lower Explicit/Time "
              "step safety, now "
           << prm.safety << ", would only add mass)";
    else
      text << "lower Explicit/Time step safety (now " << prm.safety << ")";
    return text.str();
  }



  double
  ExplicitDynamics::uniform_time(const double tau) const
  {
    // sigma' = tau' / g(tau) with the speed g(tau) = 1 - a tau / T_s,
    // a = 1 - End speed fraction
    const double a = 1. - prm.end_speed_fraction;
    if (a == 0.)
      return tau;
    return -scene_end / a * std::log1p(-a * tau / scene_end);
  }



  double
  ExplicitDynamics::slowed_time(const double sigma) const
  {
    const double a = 1. - prm.end_speed_fraction;
    if (a == 0.)
      return sigma;
    return -scene_end / a * std::expm1(-a * sigma / scene_end);
  }



  std::pair<double, double>
  ExplicitDynamics::ramp() const
  {
    const double T  = prm.loading_time;
    const double tr = prm.ramp_fraction * T;
    return {tr, uniform_time(scene_end) / (T - tr / 2.)};
  }



  double
  ExplicitDynamics::scene_time(const double t) const
  {
    // sigma' = k s(t / t_r) with the smooth step s(x) = 3x^2 - 2x^3 up to the
    // ramp's end t_r, k afterwards; int_0^x s = x^3 - x^4/2
    const auto [tr, k] = ramp();
    if (t <= 0.)
      return 0.;
    if (t < tr)
      {
        const double x = t / tr;
        return slowed_time(k * tr * (x * x * x - x * x * x * x / 2.));
      }
    return slowed_time(k * (tr / 2. + (t - tr)));
  }



  double
  ExplicitDynamics::physical_time(const double tau) const
  {
    const auto [tr, k] = ramp();
    if (tau <= 0.)
      return 0.;
    const double sigma = uniform_time(tau);
    if (sigma >= k * tr / 2.)
      return sigma / k + tr / 2.;
    // inside the ramp: bisection on the monotone x^3 - x^4/2
    const double target = sigma / (k * tr);
    double       lo = 0., hi = 1.;
    for (unsigned int i = 0; i < 60; ++i)
      {
        const double x                                      = (lo + hi) / 2.;
        (x * x * x - x * x * x * x / 2. < target ? lo : hi) = x;
      }
    return tr * (lo + hi) / 2.;
  }



  double
  ExplicitDynamics::target_step_at(const double scene_time) const
  {
    return prm.loading_time / prm.n_steps *
           interpolate(step_profile, scene_time);
  }



  void
  ExplicitDynamics::renew_mass(ExplicitSystem &system)
  {
    const TrilinosWrappers::MPI::Vector old_mass = mass;
    stable = system.update_mass(scaled ? target_step / prm.safety : 0., mass);
    // mass added during the run keeps each node's velocity: mass scaling is
    // a numerical device of the quasi-static solution, whose velocity field
    // is the loading's; keeping the momentum instead slows the nodes that
    // gain mass at once, and the compact is kicked (doc/theory.md, section
    // 10). The kinetic energy this adds is booked with the damping work.
    if (velocity.size() == mass.size() && old_mass.size() == mass.size())
      for (unsigned int i = 0; i < mass.locally_owned_size(); ++i)
        {
          const double v = velocity.begin()[i];
          w_damping -= (mass.begin()[i] - old_mass.begin()[i]) * v * v / 2.;
        }
    // the requested step where the mass scaling reached it, else the
    // stable step times the safety factor
    step =
      scaled ? std::min(target_step, prm.safety * stable) : prm.safety * stable;
    inverse_mass.reinit(mass);
    for (unsigned int i = 0; i < mass.locally_owned_size(); ++i)
      inverse_mass.begin()[i] =
        mass.begin()[i] > 0. ? 1. / mass.begin()[i] : 0.;
  }



  double
  ExplicitDynamics::start(ExplicitSystem                      &system,
                          const TrilinosWrappers::MPI::Vector &u,
                          const bool                           scaled_mass)
  {
    scaled      = scaled_mass;
    target_step = target_step_at(0.);
    renew_mass(system);
    velocity.reinit(mass);
    r_internal.reinit(mass);
    r_external.reinit(mass);
    previous_u.reinit(mass);
    time      = 0.;
    last_step = 0.;
    n_steps   = 0;
    kinetic = w_internal = w_external = w_damping = 0.;
    system.forces(u, 0., 0., 0., r_internal, r_external);
    return step;
  }



  ExplicitDynamics::Account
  ExplicitDynamics::advance(ExplicitSystem                &system,
                            TrilinosWrappers::MPI::Vector &u,
                            const double                   target)
  {
    target_step = target_step_at(target);
    renew_mass(system);
    const double       t_end = physical_time(target);
    const unsigned int n =
      std::max(1., std::ceil((t_end - time) / step * (1. - 1e-9)));
    const double h = (t_end - time) / n;

    const unsigned int size  = u.locally_owned_size();
    double            *x     = u.begin();
    double            *v     = velocity.begin();
    double            *du    = previous_u.begin();
    const double      *m     = mass.begin();
    const double      *m_inv = inverse_mass.begin();
    double            *ri    = r_internal.begin();
    double            *re    = r_external.begin();
    for (unsigned int k = 0; k < n; ++k)
      {
        const double h_avg = (last_step + h) / 2.;
        const double a     = 1. - damping * h_avg / 2.;
        const double b     = 1. / (1. + damping * h_avg / 2.);
        double       wi = 0., we = 0., wd = 0.;
        for (unsigned int i = 0; i < size; ++i)
          {
            const double v_old = v[i];
            v[i] = (a * v_old - h_avg * m_inv[i] * (ri[i] + re[i])) * b;
            const double v_mid = (v_old + v[i]) / 2.;
            wd += damping * m[i] * v_mid * v_mid * h_avg;
            du[i] = h * v[i];
            x[i] += du[i];
            // the first half of the trapezoidal work of this step
            wi += ri[i] * du[i];
            we -= re[i] * du[i];
          }
        const double tau_old = scene_time(time);
        time += h;
        last_step = h;
        ++n_steps;
        // the station is hit exactly, without the round-off of the sum
        const double tau = (k + 1 == n) ? target : scene_time(time);
        try
          {
            system.forces(u, tau, tau - tau_old, h, r_internal, r_external);
          }
        catch (const std::exception &e)
          {
            std::ostringstream text;
            text << "explicit integration failed at t = " << time << " s (step "
                 << n_steps << "): " << e.what()
                 << "; the run is probably unstable: " << remedy()
                 << "; if it fails again near the same stroke, a cell is "
                    "being crushed (scripts/postprocess/cell_volume.py lists "
                    "the cells' volume ratios; doc/performance.md)";
            throw std::runtime_error(text.str());
          }
        for (unsigned int i = 0; i < size; ++i)
          {
            wi += ri[i] * du[i];
            we -= re[i] * du[i];
          }
        w_internal += wi / 2.;
        w_external += we / 2.;
        w_damping += wd;

        // an instability grows by a large factor per step: look every 32
        // steps whether the kinetic energy ran away from the work put in
        if (n_steps % 32 == 0 || k + 1 == n)
          {
            double ke = 0.;
            for (unsigned int i = 0; i < size; ++i)
              ke += m[i] * v[i] * v[i] / 2.;
            // the integrator's energy identity holds to O(h^2) in a stable
            // run; an instability breaks it as its energy grows
            const double sums[3] = {Utilities::MPI::sum(ke, comm),
                                    Utilities::MPI::sum(w_internal, comm),
                                    Utilities::MPI::sum(w_external, comm)};
            ke                   = sums[0];
            const double work_in = system.external_work();
            const double scale   = std::max(
              {std::abs(work_in), std::abs(sums[1]), std::abs(sums[2])});
            const double identity = sums[2] - sums[0] - sums[1] -
                                    Utilities::MPI::sum(w_damping, comm);
            const bool unbounded = !std::isfinite(ke) ||
                                   !std::isfinite(identity) ||
                                   ke > 10. * scale + 1e-9 ||
                                   std::abs(identity) > 0.1 * scale + 1e-9;
            if (Utilities::MPI::max(unbounded ? 1 : 0, comm) > 0)
              {
                std::ostringstream text;
                text << "explicit integration unstable at t = " << time
                     << " s (step " << n_steps << "): kinetic energy " << ke
                     << " mJ against " << work_in << " mJ of work put in; "
                     << remedy();
                throw std::runtime_error(text.str());
              }
          }
      }

    // kinetic energy at the station: v_n from the last half step and the
    // acceleration at u_n
    double ke = 0.;
    for (unsigned int i = 0; i < size; ++i)
      {
        const double v_n = (v[i] - h / 2. * m_inv[i] * (ri[i] + re[i])) /
                           (1. + damping * h / 4.);
        ke += m[i] * v_n * v_n / 2.;
      }
    Account account;
    account.kinetic          = Utilities::MPI::sum(ke, comm);
    account.internal         = Utilities::MPI::sum(w_internal, comm);
    account.external_on_mesh = Utilities::MPI::sum(w_external, comm);
    account.damping          = Utilities::MPI::sum(w_damping, comm);
    account.steps            = n_steps;
    account.interval_steps   = n;
    account.step             = h;
    account.stable_step      = stable;
    account.time             = time;
    return account;
  }



  ExplicitDynamics::State
  ExplicitDynamics::state() const
  {
    auto values = [](const TrilinosWrappers::MPI::Vector &v) {
      return std::vector<double>(v.begin(), v.end());
    };
    State s;
    s.velocity   = values(velocity);
    s.internal   = values(r_internal);
    s.external   = values(r_external);
    s.mass       = values(mass);
    s.time       = time;
    s.last_step  = last_step;
    s.steps      = n_steps;
    s.kinetic    = kinetic;
    s.w_internal = w_internal;
    s.w_external = w_external;
    s.w_damping  = w_damping;
    return s;
  }



  void
  ExplicitDynamics::set_state(const State &saved, const bool with_mass)
  {
    auto restore = [](const std::vector<double>     &values,
                      TrilinosWrappers::MPI::Vector &v) {
      AssertDimension(values.size(), v.locally_owned_size());
      std::copy(values.begin(), values.end(), v.begin());
    };
    restore(saved.velocity, velocity);
    restore(saved.internal, r_internal);
    restore(saved.external, r_external);
    if (with_mass)
      restore(saved.mass, mass);
    time       = saved.time;
    last_step  = saved.last_step;
    n_steps    = saved.steps;
    kinetic    = saved.kinetic;
    w_internal = saved.w_internal;
    w_external = saved.w_external;
    w_damping  = saved.w_damping;
  }
} // namespace densify
