// The explicit method's force control (PunchControl::drive()) on a model
// compact: a node of mass M = 1 t on a spring K_c = 200 N/mm to the ground,
// pressed by the punch through a contact spring k = 1000 N/mm that only
// pushes, F = k max(0, d - x), integrated by central differences with the
// mass-proportional damping c = sqrt(K_c / M) (a damping ratio of 0.5) in
// steps of 1 ms, stations of 100 steps; the punch's mass k h^2, as the
// Simulator gives it (the stiffest contact spring times the step squared).
// The punch follows the displacement history 1 mm/s, then the force window
// (0.5, 1.5] s at 100 N, then the history again. Checked:
// 1. before the window the punch follows the history exactly;
// 2. in the window the station's mean force is within 0.5 % of the target
//    from its second station on (miss() below 5e-3), and the punch comes to
//    rest at the equilibrium travel F*/K_c + F*/k = 0.6 mm within 1e-3 mm:
//    the punch presses the node with the target as a load;
// 3. after the window the history goes on from where the window left the
//    punch (the travel continuous to 1e-12 mm, then 1 mm/s);
// 4. a checkpoint of the control within the window, read into a new
//    control, continues to the same travels to the last bit;
// 5. a target far above what the punch reaches at its largest speed
//    (0.05 mm/s): each step moves it by that speed times the step, and
//    miss() is 0 (a servo press approaches at its speed, by intent);
// 6. a window that ends within a station: the station's end travel is the
//    history's, shifted where the window left the punch.
#include <densify/contact/punch_control.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

namespace
{
  using densify::PunchControl;

  constexpr double k = 1000., K_c = 200., M = 1., h = 1e-3;
  const double     c = std::sqrt(K_c / M);

  /// The model compact's node: position, half-step velocity, and the
  /// contact force on the punch.
  struct Node
  {
    double x = 0., v = 0., force = 0.;
  };

  /// One explicit step to the time @p t: the punch from the last force,
  /// the node by central differences, then the new contact force.
  void
  step(PunchControl &control, Node &node, const double t)
  {
    control.drive(t, h, h, k * h * h, c);
    const double a = (node.force - K_c * node.x) / M;
    node.v         = ((1. - c * h / 2.) * node.v + h * a) / (1. + c * h / 2.);
    node.x += h * node.v;
    node.force = k * std::max(0., control.travel(t) - node.x);
    control.observe(node.force);
  }

  /// The stations from @p first to @p last (each 100 steps of h); returns
  /// the travels after every step, and prints each station if @p print.
  std::vector<double>
  run(PunchControl      &control,
      Node              &node,
      const unsigned int first,
      const unsigned int last,
      const bool         print,
      bool              &ok)
  {
    std::vector<double> travels;
    for (unsigned int s = first; s <= last; ++s)
      {
        const double t_end = 0.1 * s;
        control.plan(t_end);
        double mean = 0.;
        for (unsigned int n = 1; n <= 100; ++n)
          {
            const double t = 0.1 * (s - 1) + n * h;
            step(control, node, n == 100 ? t_end : t);
            mean += node.force / 100.;
            travels.push_back(control.travel(t));
          }
        control.accept(mean);
        const double d = control.travel(t_end);
        if (print)
          std::cout << std::fixed << std::setprecision(1) << "t " << t_end
                    << " s: travel " << std::setprecision(5) << d
                    << " mm, mean force " << std::setprecision(3) << mean
                    << " N, miss " << std::setprecision(5) << control.miss()
                    << std::endl;
        // 1. the history before the window
        if (t_end <= 0.5 + 1e-12 && std::abs(d - t_end) > 1e-12)
          ok = false;
        // 2. the target from the window's second station on
        if (t_end > 0.65 && t_end < 1.5 + 1e-12 &&
            (std::abs(mean / 100. - 1.) > 5e-3 || control.miss() > 5e-3))
          ok = false;
      }
    return travels;
  }
} // namespace



int
main()
{
  bool       ok   = true;
  const auto make = [](const double target, const double max_speed) {
    PunchControl control({{0., 0.}, {2., 2.}},
                         {{{0.5, target}, {1.5, target}}},
                         1e-3,
                         0.01,
                         max_speed);
    control.set_dynamic(true);
    return control;
  };

  PunchControl control = make(100., 5.);
  Node         node;
  run(control, node, 1, 7, true, ok);
  // 4. a checkpoint within the window
  std::stringstream saved;
  {
    boost::archive::binary_oarchive archive(saved);
    archive << control;
  }
  const Node                node_saved = node;
  const std::vector<double> straight   = run(control, node, 8, 17, true, ok);
  const double              at_rest    = straight[799];
  // 3. after the window: continuous, then the history's 1 mm/s
  const double after = straight[800], later = straight.back();
  const bool   continuous = std::abs(after - (at_rest + h)) < 1e-12 &&
                          std::abs(later - (at_rest + 0.2)) < 1e-12;
  std::cout << std::setprecision(6) << "at the window's end " << at_rest
            << " mm (equilibrium 0.6); after it " << after << " mm, at 1.7 s "
            << later << " mm" << std::endl;
  ok = ok && std::abs(at_rest - 0.6) < 1e-3 && continuous;

  PunchControl restored = make(100., 5.);
  {
    boost::archive::binary_iarchive archive(saved);
    archive >> restored;
  }
  Node       node_restored = node_saved;
  const bool same = run(restored, node_restored, 8, 17, false, ok) == straight;
  std::cout << "resumed from the checkpoint at 0.7 s: "
            << (same ? "the same travels" : "OTHER travels") << std::endl;
  ok = ok && same;

  // 5. at the largest speed
  PunchControl slow = make(1000., 0.05);
  Node         slow_node;
  run(slow, slow_node, 1, 5, false, ok);
  double       worst = 0., before = slow.travel(0.5);
  const double t0 = 0.5;
  slow.plan(0.6);
  for (unsigned int n = 1; n <= 100; ++n)
    {
      step(slow, slow_node, t0 + n * h);
      const double now = slow.travel(t0 + n * h);
      worst            = std::max(worst, std::abs(now - before - 0.05 * h));
      before           = now;
    }
  slow.accept(slow_node.force);
  std::cout << std::scientific << std::setprecision(2)
            << "at the largest speed: move per step off 0.05 mm/s x 1 ms by "
            << "at most " << worst << " mm; force " << std::fixed
            << std::setprecision(2) << slow_node.force
            << " N against 1000 N; miss " << slow.miss() << std::endl;
  ok = ok && worst < 1e-15 && slow.miss() == 0.;

  // 6. a window that ends within a station: the station's end travel is
  // the history's, shifted where the window left the punch
  PunchControl short_window(
    {{0., 0.}, {2., 2.}}, {{{0.5, 100.}, {0.55, 100.}}}, 1e-3, 0.01, 5.);
  short_window.set_dynamic(true);
  Node short_node;
  run(short_window, short_node, 1, 6, false, ok);
  const double end_travel = short_window.travel(0.6);
  double       left       = 0.;
  {
    // the travel where the window ended, from the same run again
    PunchControl again(
      {{0., 0.}, {2., 2.}}, {{{0.5, 100.}, {0.55, 100.}}}, 1e-3, 0.01, 5.);
    again.set_dynamic(true);
    Node again_node;
    run(again, again_node, 1, 5, false, ok);
    again.plan(0.6);
    for (unsigned int n = 1; n <= 50; ++n)
      step(again, again_node, 0.5 + n * h);
    left = again.travel(0.55);
  }
  std::cout << std::setprecision(6) << "a window ending within a station: "
            << "left at " << left << " mm, the station's end " << end_travel
            << " mm (the history's 0.05 mm on)" << std::endl;
  ok = ok && std::abs(end_travel - (left + 0.05)) < 1e-12;

  std::cout << (ok ? "punch_control: passed" : "punch_control: FAILED")
            << std::endl;
  return ok ? 0 : 1;
}
