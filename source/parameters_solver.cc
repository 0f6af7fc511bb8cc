// Declaration of the parameters of the solution methods: Solver (the
// implicit method's Newton and linear solvers) and Explicit (explicit
// dynamics).
#include <densify/parameters.h>

namespace densify
{
  void
  Parameters::declare_solution_method(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    {
      prm.add_parameter(
        "Method",
        solver.method,
        "implicit: quasi-static equilibrium by Newton's method at every load "
        "step (the entries below). explicit: central-difference dynamics "
        "with a lumped mass, mass scaling and penalty contact over the same "
        "element, material and contact law, no linear solve (subsection "
        "Explicit; doc/theory.md), for high-speed compaction where inertia "
        "matters; the load steps become the stations where statistics, "
        "graphics and checkpoints are written.",
        Patterns::Selection("implicit|explicit"));
      prm.add_parameter(
        "Linear solver",
        solver.linear_solver,
        "cg-amg: Trilinos CG preconditioned by ML algebraic multigrid with "
        "the six rigid-body modes (scales to large problems); gmres-amg: "
        "the same with GMRES, for nonsymmetric tangents (Contact/Friction "
        "tangent = auto, consistent or secant-start); direct: MUMPS (a few "
        "thousand unknowns); "
        "gmres-lu: GMRES preconditioned by the MUMPS factorization of an "
        "earlier tangent, factorized anew when GMRES needs more than 20 "
        "iterations, which saves factorizations where the tangent changes "
        "little (the paper's scenes); auto: gmres-amg where friction acts with "
        "a tangent that keeps its pressure coupling (Contact/Friction tangent "
        "= auto, consistent or secant-start) or where Contact/Geometric "
        "tangent = true, cg-amg otherwise.",
        Patterns::Selection("auto|cg-amg|gmres-amg|direct|gmres-lu"));
      prm.add_parameter("Linear tolerance",
                        solver.linear_tolerance,
                        "CG and GMRES stop when the residual falls below this "
                        "times the right-hand side norm (dimensionless, "
                        "1e-16 to 1). Larger: cheaper solves, more Newton "
                        "iterations.",
                        Patterns::Double(1e-16, 1.));
      prm.add_parameter(
        "Adaptive linear tolerance",
        solver.adaptive_linear_tolerance,
        "true: inexact Newton: each Newton iteration solves the linear "
        "system only as accurately as the convergence of the residual so "
        "far can use (Eisenstat-Walker: 0.9 (|R_k|/|R_k-1|)^2, between "
        "Linear tolerance and 1e-2, and no tighter than the Newton target "
        "needs). The converged answer meets the same Newton tolerance; the "
        "Krylov solvers need fewer iterations, gmres-lu fewer "
        "factorizations. No effect with direct.");
      prm.add_parameter("Maximum linear iterations",
                        solver.max_linear_iterations,
                        "Maximum number of CG or GMRES iterations per linear "
                        "solve (integer >= 1); raise it when a linear solve "
                        "stops on it.",
                        Patterns::Integer(1));
      prm.add_parameter(
        "Reuse AMG",
        solver.reuse_amg,
        "true: keep the AMG hierarchy across Newton iterations and load "
        "steps until CG needs more than twice the iterations it needed "
        "right after the last setup (plus 10); false: a new setup for every "
        "linear solve.");
      prm.add_parameter(
        "Newton tolerance",
        solver.newton_tolerance,
        "Newton stops when the l2 norm of the out-of-balance force falls "
        "below this times the larger of the internal and contact force "
        "norms (dimensionless, 1e-16 to 1; the paper's scenes: 1e-6). "
        "Smaller: more accurate equilibrium, more iterations.",
        Patterns::Double(1e-16, 1.));
      prm.add_parameter("Maximum Newton iterations",
                        solver.max_newton_iterations,
                        "Maximum Newton iterations per multiplier update "
                        "(integer >= 1); an increment that needs more is cut "
                        "back (the paper's scenes: 60).",
                        Patterns::Integer(1));
      prm.add_parameter(
        "Line search",
        solver.line_search,
        "How far each Newton iteration goes along its correction du. "
        "residual: halve the step until the out-of-balance force |R| falls "
        "(monotone, robust, but short steps where a full step closes new "
        "contact points). energy: the step s where R(u + s du).du, the "
        "derivative of the incremental energy along du, has fallen to half "
        "its size at s = 0 or below (regula falsi, at most 9 trials), so "
        "|R| may rise for an iteration; for many closing contacts (the "
        "paper's scenes). Where du is no descent direction the residual "
        "search is used.",
        Patterns::Selection("residual|energy"));
      prm.add_parameter(
        "Stabilisation",
        solver.stabilisation,
        "beta >= 0 (dimensionless): the Newton tangent (never the residual) "
        "gets beta*E/D^2 times the mass matrix of each particle (E its "
        "Young's modulus, D its diameter), so that a particle without "
        "contact does not make the system singular. The converged state is "
        "not biased; the force it contributes to the last Newton correction "
        "is reported. Raise it when a free particle makes the solve fail.",
        Patterns::Double(0.));
      prm.add_parameter(
        "Pseudo-transient continuation",
        solver.continuation,
        "How Newton gets past a state where its line search stalls, e.g. a "
        "faceted sphere that must tip over or a ring of nodes that closes "
        "and opens in turn. The continuation solves (K + beta*E/D^2*M) du "
        "= -R and takes the whole step, with beta starting at Solver/Pseudo "
        "mass and falling with the residual, so the iterates move like an "
        "overdamped body to a stable equilibrium; the residual is never "
        "changed, so the converged state is an equilibrium of the scene "
        "with no added force. off: never. fallback: an increment whose "
        "Newton solve fails is retried once at the same size with it, "
        "before it is cut back. always: every increment (slower; for "
        "scenes that fail often).",
        Patterns::Selection("off|fallback|always"));
      prm.add_parameter(
        "Pseudo mass",
        solver.pseudo_mass,
        "beta > 0 (dimensionless), the factor of the pseudo mass E/D^2*M "
        "(E Young's modulus, D diameter, M the particle's mass matrix at "
        "unit density) in the first iteration of the pseudo-transient "
        "continuation. Larger: shorter, safer first steps and more "
        "iterations; smaller: closer to plain Newton. Change it only if "
        "the continuation itself fails.",
        Patterns::Double(1e-12));
      prm.add_parameter(
        "Reproducible",
        solver.reproducible,
        "true: the direct solvers (Linear solver = direct or gmres-lu) "
        "gather the matrix on rank 0 and factorize it there with sequential "
        "MUMPS, so that a run on several MPI ranks gives the same result "
        "every time; false: MUMPS works on all ranks (faster on several "
        "ranks), whose asynchronous scheduling changes the round-off from "
        "run to run. No effect on one rank or with the AMG solvers, which "
        "repeat exactly anyway.",
        Patterns::Bool());
    }
    prm.leave_subsection();

    prm.enter_subsection("Explicit");
    {
      prm.add_parameter(
        "Loading time",
        explicit_dynamics.loading_time,
        "Physical duration of the whole load history (Time stepping/End "
        "time), in s (> 0). With mass scaling it only sets the units of the "
        "scaled mass; with Mass scaling = none it sets the punch speed, so "
        "that inertia enters (high-speed compaction).",
        Patterns::Double(1e-12));
      prm.add_parameter(
        "Number of steps",
        explicit_dynamics.n_steps,
        "Explicit time steps over the whole load history when mass scaling "
        "sets the step (integer >= 10). More steps: a slower load against "
        "the particles' vibrations, so less kinetic energy and a result "
        "closer to the quasi-static one, at proportional cost.",
        Patterns::Integer(10));
      prm.add_parameter(
        "Mass scaling",
        explicit_dynamics.mass_scaling,
        "selective: the density of each element whose stable time step is "
        "below the target step (Loading time / Number of steps) is raised "
        "until it reaches it; uniform: every element's density by the one "
        "factor the smallest element needs; none: physical densities, the "
        "stable step sets the number of steps (for high-speed compaction). "
        "The added mass is reported.",
        Patterns::Selection("selective|uniform|none"));
      prm.add_parameter(
        "Time step safety",
        explicit_dynamics.safety,
        "Time step as a fraction of the stable step computed from the "
        "elements and the contact springs (dimensionless, 0 < s <= 10). "
        "That step is a lower bound of the true limit (doc/theory.md), so "
        "values somewhat above 1 may still run; a run that goes unstable is "
        "stopped with a message, lower it then.",
        Patterns::Double(1e-3, 10.));
      prm.add_parameter(
        "Ramp fraction",
        explicit_dynamics.ramp_fraction,
        "Fraction of the loading time over which the punch velocity rises "
        "from zero along a smooth step (dimensionless, 0 <= f < 1; 0: the "
        "punch starts at full speed).",
        Patterns::Double(0., 0.999));
      prm.add_parameter(
        "End speed fraction",
        explicit_dynamics.end_speed_fraction,
        "The scene-time rate (the punch speed, for a punch moving at a "
        "constant rate in the scene) at the end of the load history as a "
        "fraction of its value after the ramp (dimensionless, 0.01 <= r <= "
        "1); in between it falls linearly with the scene time. r < 1 gives "
        "the dense end of a compaction, where the forces rise steeply, more "
        "of the Number of steps: at r = 0.25 the last fifth of the stroke "
        "takes about a third of them instead of a fifth. 1: constant rate.",
        Patterns::Double(0.01, 1.));
      prm.add_parameter(
        "Step profile",
        explicit_dynamics.step_profile,
        "Where mass scaling sets the step: the target step (Loading time / "
        "Number of steps) times a factor, piecewise linear in the scene "
        "time, as 'time:factor' pairs (time in s as Time stepping/End time, "
        "factor 0 < f <= 1; constant beyond the first and last time). Each "
        "station's step is the target at its end time. A factor f < 1 takes "
        "1/f times the steps there and scales the mass by f^2, so less "
        "inertia: for the dense end of a compaction, where cells meet Mesh/"
        "Cell volume barrier and the force rises steepest, e.g. '0:1, "
        "0.78:1, 0.8:0.4' where Time stepping/End time is 0.8. 0:1: the "
        "target step throughout.",
        Patterns::Anything());
      prm.add_parameter(
        "Damping ratio",
        explicit_dynamics.damping_ratio,
        "Mass-proportional damping, as a fraction of the critical damping of "
        "a particle's lowest compression mode (dimensionless, 0 <= z <= 1; "
        "0: none). Raise it to calm vibrations towards a quasi-static "
        "answer; its work is reported in statistics.csv.",
        Patterns::Double(0., 1.));
      prm.add_parameter(
        "Contact stiffness",
        explicit_dynamics.contact_stiffness,
        "Sets the contact penalty of explicit runs: the squared frequency of "
        "the stiffest contact spring as this fraction of the elements' "
        "largest one (dimensionless, 1e-6 to 100); the stable step includes "
        "the springs. Larger: less penetration (the penalty's force bias "
        "falls as 1 / value) but, at a given Number of steps, more added "
        "mass and so more inertia in the forces: raise it together with "
        "Number of steps. auto: for each material its initial yield stress "
        "over Young's modulus divided by 1.44e-4 (at least 1; 1 for laws "
        "that do not yield), so that the penalty's penetration relative to "
        "the element is alike in every material (the presets: Sn 4.99, Cu "
        "1.96, Fe 1.65); for the dense stage of a press and for mixtures of "
        "materials.",
        Patterns::Anything());
      prm.add_parameter(
        "Contact multiplier steps",
        explicit_dynamics.multiplier_steps,
        "Each contact point's multiplier lambda (the pressure is p = lambda - "
        "eps g) follows its pressure over about this many explicit steps N "
        "(integer >= 0), lambda += (p - lambda) / N: the penetration of "
        "lasting contacts vanishes, so the soft penalty of explicit runs "
        "does not bias the forces. This integral action can drive an "
        "undamped elastic contact unstable (plastic compaction damps it; "
        "doc/theory.md); check KE/IE. 0: pure penalty (penetration p / "
        "eps).",
        Patterns::Integer(0));
      prm.add_parameter(
        "Maximum kinetic energy ratio",
        explicit_dynamics.max_kinetic_ratio,
        "The quasi-static guard of runs whose mass scaling sets the step "
        "(Mass scaling = selective or uniform). It judges from the first "
        "station whose upper punch force gives the compact a mean axial "
        "stress of a tenth of the weakest particle's initial yield stress "
        "(for laws that do not yield, of E / 1000, the stress of an elastic "
        "strain of 1e-3) over the die's bore (without a die, over the "
        "particles' cross-sections): before it a loose bed rearranges, "
        "which mass scaling makes inertial. From there "
        "on, at each station, the kinetic energy gained since that first "
        "station may be at most this fraction of the internal work done "
        "since (dimensionless, 0 <= r <= 10; 0: not checked): what the "
        "rearrangement left moving is not counted. A run that leaves it is "
        "not quasi-static: it stops with exit code 1, names the entry to "
        "raise (Number of steps) and keeps a checkpoint of the last station "
        "within the limits. Mass scaling = none (high-speed compaction, "
        "where inertia is part of the answer) is not checked.",
        Patterns::Double(0., 10.));
      prm.add_parameter(
        "Maximum force imbalance",
        explicit_dynamics.max_force_imbalance,
        "The quasi-static guard's second limit: the upper punch force may "
        "differ from the lower punch force plus the die wall's axial force "
        "by at most this fraction of the upper punch force, each force the "
        "mean over the last ten stations (so that the vibrations of a loose "
        "packing cancel and a lasting imbalance does not); dimensionless, 0 "
        "<= r <= 10; 0: not checked. A quasi-static compact carries the "
        "upper punch's load to the lower punch and the die wall. Same stop "
        "and scope as Maximum kinetic energy ratio; stations whose upper "
        "punch force is below the force from which it judges (an unloading) "
        "are not checked.",
        Patterns::Double(0., 10.));
      prm.add_parameter(
        "Maximum force control error",
        explicit_dynamics.max_force_control_error,
        "The quasi-static guard's third limit, for a punch under force or "
        "pressure control (Tools/Upper punch or Lower punch/Force history, "
        "Pressure history): its force at a station may miss the target by "
        "at most this fraction of the larger of the target and the largest "
        "punch force so far, from the second station of each force window "
        "on (the first starts from the state before the window); "
        "dimensionless, 0 <= r <= 10; 0: not checked. The punch presses the "
        "compact with the target as a load, so a run with too few steps per "
        "station lags behind a changing target or rings about it. Same stop "
        "and scope as Maximum kinetic energy ratio.",
        Patterns::Double(0., 10.));
    }
    prm.leave_subsection();
  }
} // namespace densify
