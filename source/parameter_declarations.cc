// The declaration of every parameter of a run: the subsections of the
// components that own them (Material, Contact) and the rest.
#include <densify/contact/contact_parameters.h>
#include <densify/material/material_parameters.h>
#include <densify/parameters.h>

namespace densify
{
  void
  Parameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Scene");
    prm.add_parameter(
      "Fidelity",
      scene.fidelity,
      "One knob for accuracy against run time: draft, standard or reference "
      "set the element size, load steps, Newton tolerance, contact penalty "
      "and solver settings recommended by doc/accuracy.md (the banner prints "
      "what it set), but only those entries that the parameter file and "
      "--set leave unset: each stays overridable. as set: nothing changes. "
      "The sizes and step counts suit 2.5 mm particles and the paper's "
      "1.28 mm stroke; change it to trade accuracy for time.",
      Patterns::Selection("as set|draft|standard|reference"));
    prm.leave_subsection();

    prm.enter_subsection("Particles");
    {
      prm.add_parameter(
        "Packing",
        particles.packing,
        "How the particles are placed. 'list': the particles of Centres (or "
        "of Particle file), for a scene of your own; 'hexagonal layer': one "
        "layer of equal spheres (the first Diameter and Material) on a "
        "hexagonal lattice whose neighbours touch, clipped to the die "
        "(Tools/Die wall/Diameter), resting on the lower punch; 'random "
        "layer': Number of particles such spheres placed at random (Packing "
        "seed), then moved towards the axis until they touch; "
        "'deposited': a bed of Number of particles spheres (or up to Fill "
        "height) of Size distribution poured into the die, each dropped at "
        "random and rolled down onto the bed until it rests (frictionless "
        "sequential deposition). The initial "
        "relative density and mean coordination number are printed (also "
        "by --validate).",
        Patterns::Selection("list|hexagonal layer|random layer|deposited"));
      prm.add_parameter("Number of particles",
                        particles.n_particles,
                        "Number of spheres of Packing = random layer or "
                        "deposited (integer >= 1; with Fill height the most "
                        "to pour); other packings ignore it.",
                        Patterns::Integer(1));
      prm.add_parameter("Packing seed",
                        particles.packing_seed,
                        "Seed of the random layer, of the deposited bed and "
                        "of the random orientations of the particle file's "
                        "ellipsoids and surface particles (integer >= 0); "
                        "the same seed gives the same particles, another "
                        "seed others of the same kind.");
      prm.add_parameter(
        "Size distribution",
        particles.size_distribution,
        "Diameters of Packing = deposited: 'equal' (the first of "
        "Diameters), 'uniform' (between the two values of Diameters, "
        "'dmin, dmax') or 'log-normal' (median the first of Diameters, "
        "Diameter spread the standard deviation of ln d, truncated at three "
        "spreads); drawn with Packing seed in the order they are poured.",
        Patterns::Selection("equal|uniform|log-normal"));
      prm.add_parameter("Diameter spread",
                        particles.diameter_spread,
                        "Size distribution = log-normal only: the standard "
                        "deviation of ln d (dimensionless, 0 to 1).",
                        Patterns::Double(0., 1.));
      prm.add_parameter("Fill height",
                        particles.fill_height,
                        "Packing = deposited: pour until the next particle "
                        "would rest with its top more than this above the "
                        "lower punch (mm; that particle is left out), at "
                        "most Number of particles; 0: pour Number of "
                        "particles.",
                        Patterns::Double(0.));
      prm.add_parameter(
        "Hexagonal placement",
        particles.hexagonal_placement,
        "Packing = hexagonal layer only: where the die axis sits in the "
        "lattice: on a particle centre (d = 2.5 mm in a 20 mm die: 43 "
        "particles, the reference paper's layer), on a triangle's centre "
        "(42), on the contact point of two particles (48), or the placement "
        "that fits the most particles.",
        Patterns::Selection(
          "particle centred|hole centred|edge centred|most particles"));
      prm.add_parameter(
        "Centres",
        particles.centres,
        "Particle centres 'x,y,z; x,y,z; ...' in mm (die axis = z axis); "
        "particles may touch but not overlap, and lie between the punches "
        "and inside the die. Packing = list only; a particle file replaces "
        "it.");
      prm.add_parameter(
        "Diameters",
        particles.diameters,
        "Particle diameters in mm (> 0): one value for all particles, or a "
        "comma-separated list with one value per centre; a generated layer "
        "takes the first.");
      prm.add_parameter(
        "Materials",
        particles.materials,
        "Particle materials: Sn, Fe, Cu (presets, doc/materials.md) or "
        "custom (the constants of subsection Material); one name for all "
        "particles, or a comma-separated list with one name per centre. "
        "Used where the particle file has no material column; for a "
        "LIGGGHTS dump, atom type t gets the t-th name (or the one name).");
      prm.add_parameter(
        "Particle file",
        particles.particle_file,
        "CSV file with one particle per line, x,y,z,diameter[,material] in "
        "mm ('#' starts a comment; a header line is skipped), relative to "
        "the working directory; for scenes with many particles (Packing = "
        "list). An optional sixth column gives the shape: 'sphere'; "
        "'ellipsoid,diameter_y,diameter_z' (diameter is the one along the "
        "body x axis); or a closed surface mesh file 'NAME.stl' (mm, "
        "relative to the working directory, its centroid placed at x,y,z, "
        "the diameter column left empty). Ellipsoids and STL particles take "
        "three more columns angle_x,angle_y,angle_z (degrees, rotations "
        "about the global x, y, then z axis); without them their "
        "orientation is random from Packing seed (doc/user_guide.md, "
        "'Ellipsoids and STL particles'). A LIGGGHTS or LAMMPS text dump (first line 'ITEM:', columns "
        "x y z and radius or diameter in metres, optional id and type) is "
        "read too: its last snapshot, in mm, with the small overlaps of the "
        "DEM's soft contacts moved apart (scripts/packing/liggghts_fill.sh, "
        "doc/user_guide.md). Empty: use Centres.");
      prm.add_parameter(
        "Material fractions",
        particles.material_fractions,
        "A mixed powder 'name:fraction, name:fraction, ...' (fractions "
        ">= 0, summing to 1): that share of the particles (rounded to whole "
        "particles) gets each material, drawn at random with Material seed. "
        "Overrides Materials and the particle file's material column. "
        "Empty: no mixture.");
      prm.add_parameter("Material seed",
                        particles.material_seed,
                        "Seed of the random draw of Material fractions "
                        "(integer >= 0); the same seed gives the same "
                        "mixture, another seed another one with the same "
                        "fractions.");
      prm.add_parameter(
        "Body force",
        particles.body_force,
        "Force per volume 'bx,by,bz' on every particle, in N/mm^3, any "
        "values: e.g. gravity 0,0,-rho g (tin: 0,0,-7.15e-5) or a sideways "
        "pull. 0,0,0 switches it off at no cost.");
      prm.add_parameter(
        "Body force history",
        particles.body_force_history,
        "Dimensionless factor on Body force against time, as 't:f, t:f, "
        "...' pairs (t in s, increasing), linearly interpolated and "
        "constant beyond the ends; to ramp the body force or switch it "
        "during a run.");
    }
    prm.leave_subsection();

    prm.enter_subsection("Mesh");
    {
      prm.add_parameter(
        "Element size",
        mesh.element_size,
        "Target tetrahedron edge length away from refinement points, in mm "
        "(> 0). Smaller: more accurate contact shapes and forces, at a cost "
        "that grows about as 1/size^3 (the paper's scenes: 0.3 mm for "
        "2.5 mm spheres; the light scene: 0.5 mm).",
        Patterns::Double(1e-6));
      prm.add_parameter(
        "Refinement directions",
        mesh.refinement_directions,
        "Directions 'x,y,z; x,y,z' from each particle's centre to surface "
        "points where the mesh is refined, for contacts at known points "
        "(e.g. '0,0,1; 0,0,-1' for the poles that touch the punches). "
        "Empty: uniform mesh.");
      prm.add_parameter("Refined element size",
                        mesh.refined_element_size,
                        "Element size at the refinement points, in mm (> 0, "
                        "below Element size); used with Refinement "
                        "directions only.",
                        Patterns::Double(1e-6));
      prm.add_parameter(
        "Refinement growth",
        mesh.growth,
        "Growth of the element size with distance d (mm) from the nearest "
        "refinement point: h = min(Element size, Refined element size + "
        "growth * d); dimensionless, > 0. Smaller: a wider refined region, "
        "more elements.",
        Patterns::Double(1e-3));
      prm.add_parameter(
        "Polynomial degree",
        mesh.degree,
        "Polynomial degree of the displacement on each tetrahedron, 1 or 2 "
        "(integer): 1 (linear, with the Volumetric locking remedy; the "
        "compaction scenes) or 2 (quadratic: smoother stresses and contact "
        "pressures, several times the unknowns of the same mesh; the "
        "single-sphere and Hertz scenes).",
        Patterns::Integer(1, 2));
      prm.add_parameter(
        "Volumetric locking remedy",
        mesh.locking_remedy,
        "Remedy of the volumetric locking of linear tetrahedra under "
        "isochoric plastic flow. nodal averaging: F-bar with the volume "
        "ratio averaged over the cells around each vertex (Bonet & Burton "
        "1998; doc/theory.md); Polynomial degree = 1 only. none: plain "
        "elements. auto (keep it unless comparing): nodal averaging for "
        "Polynomial degree = 1 with Material/Model = J2 plasticity, none "
        "otherwise (quadratic tetrahedra do not lock).",
        Patterns::Selection("auto|nodal averaging|none"));
      prm.add_parameter(
        "Cell volume stabilisation",
        mesh.cell_volume_stabilisation,
        "Weight alpha of each cell's own volume change in the nodal-averaged "
        "F-bar (Volumetric locking remedy = nodal averaging), "
        "dimensionless, 0 <= alpha <= 1: each corner's material sees "
        "ln J = (1 - alpha) ln J_patch + alpha ln J_cell, so a cell keeps a "
        "bulk stiffness alpha^2 kappa against a volume change its patch does "
        "not share, the mode that lets single cells crush in the dense stage "
        "(doc/theory.md). 0: the plain F-bar; larger: cells stay fuller, but "
        "a volume constraint per cell comes back (1 is the locking plain "
        "element). The default leaves the punch force of looser packings "
        "almost unchanged (doc/verification.md, \"Cell volume "
        "stabilisation\"); Cell volume barrier stops the cells that would "
        "still crush.",
        Patterns::Double(0., 1.));
      prm.add_parameter(
        "Cell volume barrier",
        mesh.cell_volume_barrier,
        "Smallest volume ratio V/V0 a cell of the nodal-averaged F-bar "
        "(Volumetric locking remedy = nodal averaging, finite strain) "
        "reaches freely, dimensionless, 0 <= value < 1: a cell whose own "
        "volume ratio leaves [value, 1/value] meets the material's bulk "
        "modulus against the excess (ln V/V0 beyond the band), so no cell "
        "crushes however dense the compact; cells inside the band are left "
        "alone, so the answer changes only where cells would otherwise "
        "crush (doc/theory.md, \"The cells' own volume\"). 0: no barrier. "
        "A metal's elastic volume change stays far inside the default band.",
        Patterns::Double(0., 0.999));
      prm.add_parameter(
        "Maximum elements",
        mesh.max_elements,
        "A run refuses a scene whose estimated number of tetrahedra "
        "(particles times the elements of each, from its diameter and the "
        "element sizes) exceeds this (integer >= 1), before meshing; "
        "--validate prints the estimate and the memory it needs. Raise it "
        "for large scenes on a large machine.",
        Patterns::Integer(1));
    }
    prm.leave_subsection();

    declare_material_parameters(prm, material);

    prm.enter_subsection("Tools");
    {
      prm.enter_subsection("Lower punch");
      prm.add_parameter("Enabled",
                        tools.lower_enabled,
                        "Whether the rigid lower punch (the plane z = "
                        "Position, particles above it) takes part; false for "
                        "a scene without it.");
      prm.add_parameter("Position",
                        tools.lower_position,
                        "Height z of the lower punch face at t = 0, in mm "
                        "(any value below the particles); Displacement "
                        "history moves it.");
      prm.add_parameter(
        "Displacement history",
        tools.lower_displacement,
        "Upward displacement of the lower punch against time, as 't:d, t:d, "
        "...' pairs (t in s, increasing; d in mm, positive raises it), "
        "linearly interpolated and constant beyond the last time. 0:0: the "
        "punch stays. Raising it with the upper punch withdrawn pushes the "
        "compact out of the die (ejection; Tools/Die wall/Top). Within the "
        "times of a Force history or Pressure history the force rules; "
        "after them this history goes on from where the force control left "
        "the punch.");
      prm.add_parameter(
        "Force history",
        tools.lower_force,
        "Target compressive (upward) force on the lower punch against time, "
        "as 't:F, t:F, ...' pairs (t in s, increasing, within End time; F "
        "in N, >= 0), linearly interpolated. Between its first and last "
        "time the punch moves up or down to carry the target (force "
        "control); before and after, Displacement history moves it. Several "
        "windows of force control are separated by ';' ('t:F, t:F; t:F, "
        "t:F'). Empty: displacement control throughout.");
      prm.add_parameter(
        "Pressure history",
        tools.lower_pressure,
        "The same as Force history, as the mean axial stress over the die's "
        "bore, 't:p, ...' pairs (s:MPa); needs the die. Give either this or "
        "Force history.");
      prm.add_parameter(
        "Force tolerance",
        tools.lower_force_tolerance,
        "Relative tolerance of the lower punch's force control, as the "
        "upper punch's (> 0).");
      prm.add_parameter(
        "Maximum speed",
        tools.lower_max_speed,
        "Largest speed of the lower punch under force control, in mm/s "
        "(>= 0), as the upper punch's. 0: the steepest segment of its "
        "Displacement history (for a constant history, the gap between the "
        "punches over End time).");
      prm.add_parameter("Friction coefficient",
                        tools.lower_friction,
                        "Coulomb coefficient between the particles and the "
                        "lower punch (dimensionless, >= 0), or 'default' for "
                        "Contact/Friction coefficient; set a number for a "
                        "punch lubricated otherwise.");
      prm.leave_subsection();

      prm.enter_subsection("Upper punch");
      prm.add_parameter("Enabled",
                        tools.upper_enabled,
                        "Whether the rigid upper punch (a plane, particles "
                        "below it, moved by Displacement history) takes "
                        "part; false for a scene without it.");
      prm.add_parameter(
        "Initial position",
        tools.upper_initial_position,
        "Height of the upper punch face at t = 0, in mm (above every "
        "particle), or 'auto' for the top of the highest particle (the "
        "punch starts touching); a number starts with a gap.");
      prm.add_parameter(
        "Displacement history",
        tools.upper_displacement,
        "Downward displacement of the upper punch against time, as "
        "'t:d, t:d, ...' pairs (t in s, increasing; d in mm, positive "
        "compresses), linearly interpolated and constant beyond the last "
        "time. The stroke sets the final density; a flat segment holds, a "
        "falling one unloads. Within the times of a Force history or "
        "Pressure history the force rules; after them this history goes on "
        "from where the force control left the punch.");
      prm.add_parameter(
        "Force history",
        tools.upper_force,
        "Target compressive force on the upper punch against time, as "
        "'t:F, t:F, ...' pairs (t in s, increasing, within End time; F in "
        "N, >= 0), linearly interpolated. Between its first and last time "
        "the punch moves to carry the target (force control; 'press to, "
        "hold, release'); before and after, Displacement history moves it. "
        "Several windows of force control are separated by ';' ('t:F, t:F; "
        "t:F, t:F'): a punch that holds a small force in a later window "
        "follows a compact that the lower punch ejects (a hold-down). Empty: "
        "displacement control throughout.");
      prm.add_parameter(
        "Pressure history",
        tools.upper_pressure,
        "The same as Force history, as the mean axial stress over the die's "
        "bore, 't:p, ...' pairs (s:MPa); needs the die. Give either this or "
        "Force history.");
      prm.add_parameter(
        "Force tolerance",
        tools.force_tolerance,
        "Relative tolerance of the force control (dimensionless, > 0): the "
        "implicit method moves the punch until its force is within this "
        "fraction of the larger of the target and the largest force so far. "
        "Under "
        "the explicit method the punch is a rigid body pushed by the target "
        "less its contact force at every explicit step, and the quasi-static "
        "guard bounds its miss instead (Explicit/Maximum force control "
        "error).");
      prm.add_parameter(
        "Maximum speed",
        tools.max_speed,
        "Largest speed of the upper punch under force control, in mm/s "
        "(>= 0), as a servo press has: a target that needs more travel in a "
        "step is approached at this speed (the force lags its target "
        "meanwhile). 0: the steepest segment of Displacement history (for a "
        "constant history, the gap between the punches over End time).");
      prm.add_parameter(
        "Lateral displacement history",
        tools.upper_lateral_displacement,
        "Sideways (x) displacement of the upper punch against time, as "
        "'t:d, ...' pairs (s:mm); it drags the particles through friction. "
        "0:0: none; set it for a shear or sliding test.");
      prm.add_parameter("Friction coefficient",
                        tools.upper_friction,
                        "Coulomb coefficient between the particles and the "
                        "upper punch (dimensionless, >= 0), or 'default' for "
                        "Contact/Friction coefficient; set a number for a "
                        "punch lubricated otherwise.");
      prm.leave_subsection();

      prm.enter_subsection("Die wall");
      prm.add_parameter("Enabled",
                        tools.die_enabled,
                        "Whether the rigid cylindrical die wall (axis = z "
                        "axis) takes part; false for particles pressed "
                        "between the punches only (e.g. one sphere).");
      prm.add_parameter("Diameter",
                        tools.die_diameter,
                        "Inner diameter of the die, in mm (> 0; the "
                        "particles lie inside). With a generated layer it "
                        "also sets how many particles fit.",
                        Patterns::Double(1e-6));
      prm.add_parameter(
        "Top",
        tools.die_top,
        "Height z of the die's top edge, in mm (above the lower punch), or "
        "'none' for a die without end. The edge is a sharp ring; above it "
        "the wall holds nothing, so a compact pushed up past it by the lower "
        "punch leaves the die (ejection).");
      prm.add_parameter(
        "Displacement history",
        tools.die_displacement,
        "Upward (z) displacement of the die against time, as 't:d, t:d, "
        "...' pairs (t in s, increasing; d in mm, negative lowers it), "
        "linearly interpolated and constant beyond the last time. 0:0: the "
        "die stands. Lowering it below a compact that the lower punch holds "
        "strips the die off the compact (ejection by withdrawal); the die's "
        "motion along its wall drags the particles through friction.");
      prm.add_parameter("Friction coefficient",
                        tools.die_friction,
                        "Coulomb coefficient between the particles and the "
                        "die wall (dimensionless, >= 0), or 'default' for "
                        "Contact/Friction coefficient; set a number for a "
                        "die lubricated otherwise.");
      prm.leave_subsection();
    }
    prm.leave_subsection();

    declare_contact_parameters(prm, contact);

    prm.enter_subsection("Time stepping");
    {
      prm.add_parameter("End time",
                        time.end_time,
                        "Time at the end of the run, in s (> 0), the time "
                        "of the load histories. Implicit runs are "
                        "quasi-static: time only orders the load; explicit "
                        "runs map it onto Explicit/Loading time.",
                        Patterns::Double(1e-15));
      prm.add_parameter("Number of steps",
                        time.n_steps,
                        "Number of equal load steps from t = 0 to End time "
                        "(integer >= 1), each a row of statistics.csv. "
                        "More: smaller increments, easier Newton, longer "
                        "runs; raise it when many steps need cut-backs.",
                        Patterns::Integer(1));
      prm.add_parameter(
        "Maximum cut-backs",
        time.max_cutbacks,
        "A load increment that does not converge is rolled back and retried "
        "with half the increment, at most this many times in a row within "
        "one load step and never below 2^-N of a step (N this number, "
        "integer 0 to 30); the increment grows again after easy increments "
        "and every load step still ends at its own time. 0: no cut-back; "
        "raise it when a run stops on a hard step.",
        Patterns::Integer(0, 30));
    }
    prm.leave_subsection();

    declare_solution_method(prm);

    prm.enter_subsection("Output");
    {
      prm.add_parameter("Directory",
                        output.directory,
                        "Directory for statistics.csv, particles.csv, "
                        "log.txt, graphics and checkpoints, relative to the "
                        "working directory; created if missing. Give each "
                        "scene its own.");
      prm.add_parameter("Interval",
                        output.interval,
                        "Write graphics (.pvtu + .pvd) every this many load "
                        "steps and at the last step (integer >= 0; 0: "
                        "never). Larger: less disk space.",
                        Patterns::Integer(0));
      prm.add_parameter("Verbose",
                        output.verbose,
                        "true: print the residual of every Newton iteration "
                        "with the contact, slipping and yielding points (and "
                        "how many yielding points changed), and that of "
                        "every line-search trial with the largest tool and "
                        "particle penetration; and for every new "
                        "factorization of the direct solvers MUMPS's flops, "
                        "factor entries and largest front. For diagnosing a "
                        "run that converges slowly.");
      prm.add_parameter(
        "Checkpoint interval",
        output.checkpoint_interval,
        "Write a checkpoint (DIRECTORY/checkpoint/) every this many load "
        "steps, the last step included where it is a multiple (integer >= 0; "
        "0: only when the run is stopped by SIGINT, SIGTERM or "
        "--stop-after). densify --resume continues from it; from a finished "
        "run's last step, with a longer End time, Number of steps and load "
        "history.",
        Patterns::Integer(0));
    }
    prm.leave_subsection();
  }
} // namespace densify
