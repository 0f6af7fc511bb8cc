// A punch's control by displacement and force histories.
#include <densify/contact/punch_control.h>
#include <densify/parameters.h>

#include <algorithm>
#include <cmath>

namespace densify
{
  namespace
  {
    /// Times closer than this (relative) are the same.
    constexpr double time_epsilon = 1e-12;
  } // namespace



  PunchControl::PunchControl(
    const std::vector<std::pair<double, double>> &displacement)
    : PunchControl(displacement, {}, 1e-3, 0., 0.)
  {}



  PunchControl::PunchControl(
    const std::vector<std::pair<double, double>>              &displacement,
    const std::vector<std::vector<std::pair<double, double>>> &force,
    const double                                               tolerance,
    const double                                               trial_travel,
    const double                                               max_speed)
    : displacement(displacement)
    , force(force)
    , tolerance(tolerance)
    , trial_travel(trial_travel)
    , max_speed(max_speed)
    , d0(interpolate(displacement, 0.))
    , d1(d0)
    , body_travel(d0)
  {}



  bool
  PunchControl::force_controlled(const double t) const
  {
    const double eps = time_epsilon * std::max(1., std::abs(t));
    for (const auto &table : force)
      if (t > table.front().first + eps && t <= table.back().first + eps)
        return true;
    return false;
  }



  const std::vector<std::pair<double, double>> *
  PunchControl::window(const double t) const
  {
    const double eps = time_epsilon * std::max(1., std::abs(t));
    for (const auto &table : force)
      if (t >= table.front().first - eps && t <= table.back().first + eps)
        return &table;
    return nullptr;
  }



  double
  PunchControl::target(const double t) const
  {
    const auto *table = window(t);
    return table == nullptr ? 0. : interpolate(*table, t);
  }



  double
  PunchControl::displacement_travel(const double t) const
  {
    return interpolate(displacement, t) + offset;
  }



  double
  PunchControl::travel(const double t) const
  {
    // the rigid body in a force window (the explicit method); a planned
    // force-controlled move is linear in time from the accepted state;
    // elsewhere the (shifted) displacement history
    if (body_moving)
      return body_travel;
    const double eps = time_epsilon * std::max(1., std::abs(t1));
    if (!dynamic_windows && t1 > t0 && force_controlled(t1) && t >= t0 - eps &&
        t <= t1 + eps)
      return d0 + (d1 - d0) * (t - t0) / (t1 - t0);
    if (std::abs(t - t0) <= eps)
      return d0;
    return displacement_travel(t);
  }



  void
  PunchControl::plan(const double t_end,
                     const double gain,
                     const double other_travel)
  {
    t1     = t_end;
    other  = other_travel;
    has_lo = has_hi = false;
    last_side       = 0;
    if (!force_controlled(t1))
      {
        d1 = displacement_travel(t1);
        return;
      }
    // the rigid body moves itself (drive())
    if (dynamic_windows)
      {
        d1 = d0;
        return;
      }
    // the accepted state is one end of the bracket when nothing else moves:
    // a move that stays there carries its force
    const double target_force = target(t1);
    if (other == 0. && f0 < target_force)
      {
        lo_d   = d0;
        lo_f   = f0;
        has_lo = true;
      }
    else if (other == 0. && f0 > target_force)
      {
        hi_d   = d0;
        hi_f   = f0;
        has_hi = true;
      }
    // the secant stiffness's prediction, no faster than the largest speed;
    // the other punch's travel given back in full (the compact moves with
    // it)
    double move = -other;
    if (stiffness > 0.)
      move += gain * (target_force - f0) / stiffness;
    else if (target_force != f0)
      move += (target_force > f0 ? 1. : -1.) * trial_travel;
    d1 = d0 + std::clamp(move, -max_move(), max_move());
  }



  bool
  PunchControl::correct(const double f, double &scale)
  {
    scale = 1.;
    if (!force_controlled(t1))
      return true;
    const double target_force = target(t1);
    const double tol =
      tolerance * std::max(std::abs(target_force), force_scale);
    if (std::abs(f - target_force) <= tol)
      return true;
    // more travel, more force
    const int side = f < target_force ? -1 : 1;
    // at the largest speed and still short: the punch approaches the target
    // at that speed
    if ((d1 - d0) * -side >= max_move() * (1. - 1e-12))
      return true;
    const double tried = d1;
    if (side < 0 && (!has_lo || d1 > lo_d))
      {
        lo_d   = d1;
        lo_f   = f;
        has_lo = true;
      }
    if (side > 0 && (!has_hi || d1 < hi_d))
      {
        hi_d   = d1;
        hi_f   = f;
        has_hi = true;
      }
    if (has_lo && has_hi && hi_f > lo_f)
      {
        // regula falsi; an end kept twice in a row counts half (Illinois),
        // so that the other end moves too
        if (side == last_side)
          {
            if (side < 0)
              hi_f = target_force + (hi_f - target_force) / 2.;
            else
              lo_f = target_force + (lo_f - target_force) / 2.;
          }
        d1 = lo_d + (target_force - lo_f) * (hi_d - lo_d) / (hi_f - lo_f);
      }
    else
      {
        // no bracket yet (e.g. before the first contact): the secant through
        // the accepted state, at most four times this move's length further;
        // where that secant does not rise (the other punch moved the compact
        // on, and the force fell meanwhile) the last secant stiffness of two
        // accepted states; else twice the move
        const double direction = side < 0 ? 1. : -1.;
        // the travel that would carry the accepted force
        const double base   = d0 - other;
        double       length = std::abs(d1 - base);
        // a punch that carries nothing (off the compact) moves at least the
        // trial travel
        if (length < 1e-12 * std::max(1., std::abs(d0)) || f <= 0.)
          length = std::max(length, trial_travel);
        double next = d1 + direction * length;
        if (std::abs(d1 - base) > 0. && (f - f0) / (d1 - base) > 0.)
          {
            const double secant =
              d1 + (target_force - f) * (d1 - base) / (f - f0);
            if ((secant - d1) * direction > 0.)
              next =
                d1 + direction * std::min(std::abs(secant - d1), 4. * length);
          }
        else if (other != 0. && f > 0. && stiffness > 0.)
          next = d1 + (target_force - f) / stiffness;
        d1 = next;
      }
    d1        = std::clamp(d1, d0 - max_move(), d0 + max_move());
    last_side = side;
    // the new move against the tried one, from the accepted state (when
    // the other punch moves too, the tried solve's end is the start)
    if (other == 0. &&
        std::abs(tried - d0) > 1e-12 * std::max(1., std::abs(d0)))
      scale = std::clamp((d1 - d0) / (tried - d0), 0., 5.);
    return false;
  }



  void
  PunchControl::drive(const double t,
                      const double t_increment,
                      const double h,
                      const double mass,
                      const double damping)
  {
    if (!force_controlled(t))
      {
        // the history goes on from where the window left the punch
        if (body_moving)
          offset = body_travel - interpolate(displacement, t - t_increment);
        body_moving       = false;
        body_at_speed     = false;
        const double next = travel(t);
        body_speed        = h > 0. ? (next - body_travel) / h : 0.;
        body_travel       = next;
        return;
      }
    // the window's first step starts from the punch's travel and speed
    body_moving = true;
    // central differences with the particles' mass-proportional damping
    const double acceleration = (target(t) - body_force) / mass;
    body_speed = ((1. - damping * h / 2.) * body_speed + h * acceleration) /
                 (1. + damping * h / 2.);
    const double limit = max_speed * t_increment;
    double       move  = h * body_speed;
    body_at_speed      = std::abs(move) > limit;
    if (body_at_speed)
      {
        move       = std::copysign(limit, move);
        body_speed = move / h;
      }
    body_travel += move;
  }



  double
  PunchControl::max_move() const
  {
    return max_speed * (t1 - t0);
  }



  void
  PunchControl::accept(const double f)
  {
    // the rigid body's end; after a window that ended within the move, the
    // history shifted where the window left the punch (drive())
    if (body_moving)
      d1 = body_travel;
    else if (dynamic_windows && !force_controlled(t1))
      d1 = displacement_travel(t1);
    // the compact's compression over the move: both punches' travels
    const double compression = d1 - d0 + other;
    if (std::abs(compression) > 1e-12 * std::max(1., std::abs(d0)) &&
        (f - f0) / compression > 0.)
      stiffness = (f - f0) / compression;
    other        = 0.;
    d_prev       = d0;
    has_prev     = true;
    window_moves = force_controlled(t1) ? window_moves + 1 : 0;
    if (force_controlled(t1))
      offset = d1 - interpolate(displacement, t1);
    t0          = t1;
    d0          = d1;
    f0          = f;
    force_scale = std::max(force_scale, std::abs(f));
  }



  double
  PunchControl::miss() const
  {
    // a punch at its largest speed approaches its target at it, by intent
    if (window_moves < 2 || body_at_speed)
      return 0.;
    const double target_force = target(t0);
    const double scale        = std::max(std::abs(target_force), force_scale);
    return scale > 0. ? std::abs(f0 - target_force) / scale : 0.;
  }
} // namespace densify
