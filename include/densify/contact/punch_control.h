// A punch's control: its displacement history and, within the times of a
// force history, the travel that makes it carry the target force.
#pragma once

#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
#include <boost/serialization/version.hpp>

#include <utility>
#include <vector>

namespace densify
{
  /**
   * Where a punch is at each time, as its travel (the upper punch's
   * downward, the lower punch's upward: the direction in which its force
   * grows). Outside the force windows (the times of each of the force
   * history's tables, (t_first, t_last]) the punch follows the displacement
   * history; after a window, that history continues from where the force
   * control left the punch (shifted by a constant), so the travel is
   * continuous at both switches. Within a window, each move (an implicit
   * increment or an explicit station) starts from the last accepted state
   * (time, travel, force) and plans its end travel from the target force,
   * the secant stiffness of the last two accepted states and the other
   * punch's travel over the move;
   * the implicit method then corrects the travel by a bracketing secant
   * (regula falsi) until the punch carries the target within the tolerance
   * (correct()). During a move the travel is linear in time.
   *
   * The explicit method (set_dynamic()) instead follows a force window with
   * the punch as a rigid body driven by the target less the force it
   * carries, integrated with the particles' central differences step by
   * step (drive()): its mass is far below the compact's, so it presses the
   * compact with the target as a load, at most at the largest speed.
   */
  class PunchControl
  {
  public:
    /// Displacement control by @p displacement alone (s:mm, downward).
    PunchControl(const std::vector<std::pair<double, double>> &displacement = {
                   {0., 0.}});

    /**
     * @p displacement the downward travel against time (s:mm), @p force the
     * target compressive force against time (s:N), one table per force
     * window (empty: displacement control throughout), @p tolerance the
     * relative force tolerance (of the larger of the target and the largest
     * force so far), @p trial_travel the first move (mm) where no stiffness is
     * known yet (before the first contact), @p max_speed the punch's largest
     * speed under force control (mm/s): a target that needs more travel in a
     * move is approached at it, as a servo press does.
     */
    PunchControl(
      const std::vector<std::pair<double, double>>              &displacement,
      const std::vector<std::vector<std::pair<double, double>>> &force,
      const double                                               tolerance,
      const double                                               trial_travel,
      const double                                               max_speed);

    /// Whether a move that ends at @p t is force-controlled.
    bool
    force_controlled(const double t) const;

    /// The target force at @p t (N; 0 outside the force windows).
    double
    target(const double t) const;

    /// The punch's downward travel at @p t (mm).
    double
    travel(const double t) const;

    /**
     * Start a move from the accepted state to the time @p t_end: plan its
     * end travel, closing the fraction @p gain of the force's gap to the
     * target by the secant stiffness (the explicit method, which cannot
     * correct a move, takes less than all of it against overshooting).
     * @p other_travel is the other punch's travel over the move towards
     * this one (mm; e.g. the lower punch's rise for the upper punch): it
     * presses the compact as this punch's own travel does, so the plan
     * gives it back (a punch holding a force follows an ejected compact).
     */
    void
    plan(const double t_end,
         const double gain         = 1.,
         const double other_travel = 0.);

    /**
     * After a converged solve of the planned move, whose punch carried
     * @p force: true if the move is displacement-controlled, the force is
     * the target's within the tolerance, or the move is as long as the
     * largest speed allows and still short; otherwise plan another end travel
     * for the same move (a bracketing secant) and return false, with
     * @p scale the new move's length over the tried one's (in [0, 5]; 1 if
     * the tried move was none): the increment of the solution scaled by it
     * predicts the new solve's start.
     */
    bool
    correct(const double force, double &scale);

    /// Accept the planned move's end, at which the punch carries @p force.
    void
    accept(const double force);

    /**
     * Follow force windows as a rigid body (the explicit method) rather than
     * by planned moves (the implicit method).
     */
    void
    set_dynamic(const bool dynamic)
    {
      dynamic_windows = dynamic;
    }

    /**
     * The explicit method's step to the scene time @p t, reached over the
     * scene-time increment @p t_increment and the physical step @p h (s),
     * from the force of the last observe(). Within a force window the punch
     * of mass @p mass (t) under the mass-proportional damping @p damping
     * (1/s) is accelerated by the target less that force,
     * its move per step at most the largest speed times @p t_increment;
     * outside it, it follows the displacement history, which goes on from
     * where the window left the punch.
     */
    void
    drive(const double t,
          const double t_increment,
          const double h,
          const double mass,
          const double damping);

    /// The force (N) the punch carries after an explicit step, for the next
    /// drive().
    void
    observe(const double force)
    {
      body_force = force;
    }

    /// The force the punch carries at the accepted state (N).
    double
    accepted_force() const
    {
      return f0;
    }

    /// The accepted force's miss of its target, as a fraction of the larger
    /// of the target and the largest force so far; 0 after a
    /// displacement-controlled move, the first move of a force window
    /// (which starts from the state before the window) and a rigid body
    /// (drive()) at its largest speed, which approaches the target at it.
    double
    miss() const;

    /// The checkpoint's state (version 0 lacks the rigid body's).
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int version)
    {
      archive &t0 &d0 &f0 &d_prev &has_prev &stiffness &offset &force_scale &t1
        &d1 &window_moves;
      if (version >= 1)
        archive &body_travel &body_speed &body_force &body_moving;
    }

  private:
    /// The longest move to the planned end time (mm).
    double
    max_move() const;

    /// The displacement history's travel at @p t, shifted after the window.
    double
    displacement_travel(const double t) const;

    /// The force window that holds @p t (its times [first, last]), or
    /// nullptr.
    const std::vector<std::pair<double, double>> *
    window(const double t) const;

    std::vector<std::pair<double, double>>              displacement;
    std::vector<std::vector<std::pair<double, double>>> force;
    double                                              tolerance    = 1e-3;
    double                                              trial_travel = 0.;
    double                                              max_speed    = 0.;

    /// The accepted state: time, travel, force.
    double t0 = 0., d0 = 0., f0 = 0.;
    /// The travel of the accepted state before it.
    double d_prev   = 0.;
    bool   has_prev = false;
    /// The last positive secant stiffness of two accepted states (N/mm;
    /// 0: none yet).
    double stiffness = 0.;
    /// The accepted moves of the current force window (0 outside one).
    unsigned int window_moves = 0;
    /// The shift of the displacement history after the window (mm).
    double offset = 0.;
    /// The largest force accepted so far (N).
    double force_scale = 0.;
    /// The planned move's end time and travel.
    double t1 = 0., d1 = 0.;
    /// The other punch's travel over the planned move (mm): the travel of
    /// this punch that carries the accepted force is d0 - other.
    double other = 0.;

    /// Whether force windows are followed by the rigid body (drive()).
    bool dynamic_windows = false;
    /// The rigid body's travel (mm), speed (mm/s of physical time) and
    /// force (N) after the last step, and whether it is in a force window.
    double body_travel = 0., body_speed = 0., body_force = 0.;
    bool   body_moving = false;
    /// Whether the rigid body's last step was held to the largest speed.
    bool body_at_speed = false;

    /// The tries of the current move: the largest travel that carried less
    /// than the target, the smallest that carried more, and the side the
    /// last try fell on (regula falsi with the Illinois halving).
    double lo_d = 0., lo_f = 0., hi_d = 0., hi_f = 0.;
    bool   has_lo = false, has_hi = false;
    int    last_side = 0;
  };
} // namespace densify

BOOST_CLASS_VERSION(densify::PunchControl, 1)
