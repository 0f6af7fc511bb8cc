// Declaration, reading and overriding of Densify's parameters.
#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <densify/contact/friction_law.h>
#include <densify/fidelity.h>
#include <densify/ignored_parameters.h>
#include <densify/material/factory.h>
#include <densify/parameters.h>
#include <densify/utilities.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

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

    prm.enter_subsection("Material");
    {
      prm.add_parameter(
        "Model",
        material.model,
        "Constitutive model of every particle: elastic (isotropic, "
        "small-strain linear or finite-strain Hencky) or J2 plasticity "
        "(finite-strain von Mises elastoplasticity, Simo 1992; "
        "doc/theory.md). The material of each particle (Sn, Fe, Cu, custom) "
        "gives E, nu and the yield stress. J2 plasticity (needs Finite "
        "strain = true) is for compaction: single particles and layers of "
        "touching particles in a die (prm/single_layer_sn.prm); elastic for "
        "small deformations and verification (prm/hertz.prm).",
        Patterns::Selection(material_model_names()));
      prm.add_parameter(
        "Finite strain",
        material.finite_strain,
        "true: finite-strain kinematics (large rotations, Hencky strain), "
        "needed by J2 plasticity and by any large deformation. false: "
        "small-strain linear elasticity (Model = elastic only), for small "
        "deformations such as checks against linear theory.");
      prm.add_parameter(
        "Hardening",
        material.hardening,
        "Isotropic hardening of every J2 material, presets included: none "
        "(perfectly plastic, as the presets' data), linear (sigma_y = "
        "sigma0 + H eps_p, Hardening modulus) or power law (sigma_y = "
        "sigma0 + K eps_p^n, Hardening coefficient and exponent); for a "
        "powder that work-hardens.",
        Patterns::Selection("none|linear|power law"));
      prm.add_parameter("Yield stress",
                        material.yield_stress,
                        "Initial yield stress sigma0 of the material 'custom', "
                        "in MPa (> 0); the presets carry their own "
                        "(doc/materials.md).",
                        Patterns::Double(0.));
      prm.add_parameter("Hardening modulus",
                        material.hardening_modulus,
                        "Linear hardening modulus H, in MPa (>= 0); "
                        "Hardening = linear only.",
                        Patterns::Double(0.));
      prm.add_parameter("Hardening coefficient",
                        material.hardening_coefficient,
                        "Power-law hardening coefficient K, in MPa (>= 0); "
                        "Hardening = power law only.",
                        Patterns::Double(0.));
      prm.add_parameter("Hardening exponent",
                        material.hardening_exponent,
                        "Power-law hardening exponent n (dimensionless, > 0); "
                        "Hardening = power law only.",
                        Patterns::Double(1e-6));
      prm.add_parameter(
        "Young's modulus",
        material.youngs_modulus,
        "Young's modulus of the material 'custom', in MPa (> 0, at most "
        "1e7). The presets Sn, Fe and Cu carry their own values "
        "(doc/materials.md).",
        Patterns::Double(1e-12));
      prm.add_parameter("Poisson's ratio",
                        material.poissons_ratio,
                        "Poisson's ratio of the material 'custom' "
                        "(dimensionless, -1 < nu < 0.5); the presets carry "
                        "their own.",
                        Patterns::Double(-0.999, 0.499));
      prm.add_parameter(
        "Density",
        material.density,
        "Mass density of the material 'custom', in t/mm^3 (7.29e-9 is tin); "
        "used by Solver/Method = explicit only. The presets carry their own "
        "values (doc/materials.md).",
        Patterns::Double(1e-15, 1e-3));
    }
    prm.leave_subsection();

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

    prm.enter_subsection("Contact");
    {
      prm.add_parameter(
        "Penalty factor",
        contact.penalty_factor,
        "Augmented-Lagrangian penalty as a multiple of E/h (E the particle's "
        "Young's modulus in MPa, h the smallest element size in mm); "
        "dimensionless, > 0. The multiplier updates remove the penetration "
        "whatever its value. Larger: fewer multiplier updates, worse "
        "conditioned systems; change it when the updates do not reach Gap "
        "tolerance or Newton struggles.",
        Patterns::Double(1e-12));
      prm.add_parameter(
        "Gap tolerance",
        contact.gap_tolerance,
        "Largest penetration of a particle into a tool or another particle "
        "accepted at the end of a step, in mm (> 0, well below the element "
        "size); multipliers are updated until it is met. Smaller: more "
        "accurate contact, more updates. Explicit runs (no multiplier "
        "updates) print one warning at the first station above it.",
        Patterns::Double(1e-15));
      prm.add_parameter(
        "Maximum augmentations",
        contact.max_augmentations,
        "Maximum number of multiplier updates per load step (integer 0 to "
        "1000; 0: pure penalty). A step that ends above Gap tolerance prints "
        "a warning; raise it then.",
        Patterns::Integer(0, 1000));
      prm.add_parameter(
        "Friction coefficient",
        contact.friction_coefficient,
        "Coulomb friction coefficient mu between particles, and of every tool "
        "whose own Friction coefficient is 'default' (dimensionless, >= 0; "
        "the paper's scenes: 0.2). 0 switches friction off and costs "
        "nothing.",
        Patterns::Double(0.));
      prm.add_parameter(
        "Friction model",
        contact.friction_model,
        "'Coulomb': stick below mu p, slip at mu p (return map, penalty "
        "stick stiffness); 'arctangent': the paper's regularised law "
        "t = mu p (2/pi) atan(v/v0) against the sliding velocity v, for "
        "comparisons with the paper.",
        Patterns::Selection(slip_rule_names()));
      prm.add_parameter("Slip velocity",
                        contact.slip_velocity,
                        "v0 of the arctangent law, in mm/s (> 0): below it "
                        "the traction grows linearly with the velocity. "
                        "Smaller: closer to Coulomb, harder for Newton.",
                        Patterns::Double(1e-300));
      prm.add_parameter(
        "Tangential penalty factor",
        contact.tangential_penalty_factor,
        "Stick stiffness of Coulomb friction as a multiple of E/h "
        "(dimensionless, > 0): a sticking point slips elastically by "
        "t h / (factor E). Much stiffer than needed slows Newton where "
        "points slip.",
        Patterns::Double(1e-12));
      prm.add_parameter(
        "Friction tangent",
        contact.friction_tangent,
        "'symmetric': the slip tangent without its nonsymmetric coupling to "
        "the pressure and with the secant stiffness along the slip (CG "
        "works; Newton converges only linearly where points slip); "
        "'consistent': the exact one (quadratic Newton near slip, "
        "needs Solver/Linear solver = gmres-amg, gmres-lu, direct or auto); "
        "'secant-start': consistent, but each Newton solve's first "
        "iterations take the secant stiffness along the slip (where the "
        "exact tangent has none) until a correction moves no entry by more "
        "than a hundredth of half the smallest element size, which keeps a "
        "pore's slipping, yielding surface from huge corrections in dense "
        "packings; 'symmetric-secant-start': secant-start without the "
        "coupling to the pressure, symmetric for CG; 'auto' (keep it): "
        "secant-start, or symmetric-secant-start with Solver/Linear solver "
        "= cg-amg.",
        Patterns::Selection(
          "auto|symmetric|consistent|secant-start|symmetric-secant-start"));
      prm.add_parameter(
        "Geometric tangent",
        contact.geometric_tangent,
        "Whether the Newton tangent of particle-particle contact includes "
        "the rotation of the master facet's normal and the sliding of the "
        "projection point over the facet (doc/theory.md section 9). true: "
        "exact for P1 and P2 contact, quadratic Newton where contacts slide "
        "over facets, but nonsymmetric (needs Solver/Linear solver = "
        "gmres-amg, gmres-lu or direct); false: only eps n n^T and the "
        "friction law's stiffness; auto: true for frictionless particle "
        "contact unless the linear solver is cg-amg, false with friction. "
        "It changes how Newton converges, not the equations the converged "
        "state solves; where several equilibria lie near (the path of "
        "friction, an unstable frictionless packing) it can reach another "
        "one. Change it when Newton stalls on sliding contacts.",
        Patterns::Selection("auto|true|false"));
      prm.add_parameter(
        "Contact points",
        contact.contact_points,
        "Where contact with tools and other particles is evaluated on a "
        "particle's surface facets. 'vertices': at the facet corners (node "
        "to surface, weights area/3; a faceted sphere's pole touches first, "
        "so it is pressed without a spurious moment); 'Gauss points': at "
        "the facet's Gauss points (needed for P2, whose vertex weights "
        "vanish); 'auto' (keep it): vertices for P1, Gauss points for P2.",
        Patterns::Selection("auto|vertices|Gauss points"));
      prm.add_parameter(
        "Hold poles on axis",
        contact.hold_poles,
        "Springs (stiffness Penalty factor * E * h) against the free motions "
        "that frictionless contact leaves to a faceted sphere, which make "
        "Newton stall (doc/theory.md). true: the top and bottom pole "
        "vertices stay on the vertical line through the initial centre, "
        "for one sphere or a vertical stack between frictionless punches "
        "(in a stack one more spring per particle holds its spin about the "
        "vertical axis). vertical: the axis through each particle's poles "
        "stays vertical, the particle may move sideways, for frictionless "
        "layers symmetric about each particle's mid-plane. false: no "
        "springs. The springs' force is "
        "pole_force in statistics.csv; it vanishes for a state with that "
        "symmetry.",
        Patterns::Selection("false|true|vertical"));
    }
    prm.leave_subsection();

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



  namespace
  {
    /// The additional-information text of a deal.II exception, on one line.
    std::string
    one_line(const ExceptionBase &e)
    {
      std::ostringstream info;
      e.print_info(info);
      return densify::one_line(info.str());
    }
  } // namespace



  void
  read_parameters(ParameterHandler               &prm,
                  const std::string              &filename,
                  const std::vector<std::string> &overrides,
                  std::string                    *fidelity_summary)
  {
    if (std::filesystem::is_directory(filename))
      throw std::runtime_error("parameter file '" + filename +
                               "' is a directory: give a .prm file");
    std::string text;
    {
      // C stdio, whose error flag tells a file that cannot be read (such as
      // /proc/self/mem) from an empty one
      std::FILE *in = std::fopen(filename.c_str(), "rb");
      if (in == nullptr)
        throw std::runtime_error("cannot open parameter file '" + filename +
                                 "': " + std::strerror(errno));
      char        buffer[4096];
      std::size_t n;
      while ((n = std::fread(buffer, 1, sizeof(buffer), in)) > 0)
        text.append(buffer, n);
      const bool failed = std::ferror(in) != 0;
      const int  code   = errno;
      std::fclose(in);
      if (failed)
        throw std::runtime_error("cannot read parameter file '" + filename +
                                 "': " + std::strerror(code) +
                                 ": give a readable .prm file");
    }
    // a UTF-8 byte-order mark, as some editors write
    if (text.rfind("\xEF\xBB\xBF", 0) == 0)
      text.erase(0, 3);
    if (text.find_first_not_of(" \t\r\n") == std::string::npos)
      throw std::runtime_error(
        "parameter file '" + filename +
        "' is empty: give a scene (e.g. a copy of prm/default.prm; densify "
        "--print-parameters lists every entry)");
    try
      {
        std::istringstream in(text);
        prm.parse_input(in, filename, "", false);
      }
    catch (const ExceptionBase &e)
      {
        throw std::runtime_error(one_line(e) +
                                 " (densify --print-parameters lists every "
                                 "entry)");
      }

    for (const std::string &o : overrides)
      {
        const auto eq = o.find('=');
        if (eq == std::string::npos)
          throw std::runtime_error("--set '" + o +
                                   "': expected 'Subsection/Name=value'");
        const std::vector<std::string> path =
          Utilities::split_string_list(o.substr(0, eq), '/');
        const std::string value = Utilities::trim(o.substr(eq + 1));
        if (path.empty())
          throw std::runtime_error("--set '" + o + "': no entry name");
        for (unsigned int i = 0; i + 1 < path.size(); ++i)
          if (!prm.subsection_path_exists(
                std::vector<std::string>(path.begin(), path.begin() + i + 1)))
            {
              std::string sub;
              for (unsigned int j = 0; j <= i; ++j)
                sub += (j > 0 ? "/" : "") + path[j];
              throw std::runtime_error("--set '" + o + "': no subsection '" +
                                       sub +
                                       "' (densify --print-parameters lists "
                                       "every entry)");
            }
        unsigned int depth = 0;
        try
          {
            for (unsigned int i = 0; i + 1 < path.size(); ++i, ++depth)
              prm.enter_subsection(path[i]);
            prm.set(path.back(), value);
          }
        catch (const ExceptionBase &e)
          {
            for (; depth > 0; --depth)
              prm.leave_subsection();
            throw std::runtime_error("--set '" + o + "': " + one_line(e) +
                                     " (densify --print-parameters lists "
                                     "every entry)");
          }
        for (; depth > 0; --depth)
          prm.leave_subsection();
      }

    // one warning line for each entry set in the file or by --set that the
    // scene does not use
    std::set<std::string> set = entries_set_in_file(filename);
    for (const std::string &o : overrides)
      {
        std::string entry;
        for (const std::string &part :
             Utilities::split_string_list(o.substr(0, o.find('=')), '/'))
          entry += (entry.empty() ? "" : "/") + part;
        set.insert(entry);
      }
    const std::string fidelity = resolve_fidelity(prm, set);
    if (fidelity_summary != nullptr)
      *fidelity_summary = fidelity;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      for (const std::string &line : ignored_parameters(prm, set))
        std::cerr << "densify: warning: " << line << std::endl;
  }



  std::string
  parameter_fingerprint(const ParameterHandler &prm)
  {
    // the short PRM text ("subsection", "set Name = value", "end" lines),
    // flattened to "Sub/Sub/Name = value"; Output, Solver and the friction
    // and geometric tangents may change between a run and its resumption (how
    // to write, how to solve)
    std::ostringstream prm_text;
    prm.print_parameters(prm_text, ParameterHandler::ShortPRM);
    std::istringstream       in(prm_text.str());
    std::vector<std::string> path;
    std::ostringstream       text;
    for (std::string line; std::getline(in, line);)
      {
        line = Utilities::trim(line);
        if (line.rfind("subsection ", 0) == 0)
          path.push_back(Utilities::trim(line.substr(11)));
        else if (line == "end" && !path.empty())
          path.pop_back();
        else if (line.rfind("set ", 0) == 0 &&
                 (path.empty() ||
                  (path[0] != "Output" &&
                   (path[0] != "Solver" ||
                    Utilities::trim(line.substr(4, line.find('=') - 4)) ==
                      "Method"))))
          {
            const std::string entry = line.substr(4);
            const auto        eq    = entry.find('=');
            // the fidelity level stands for the entries it set, which are
            // in the fingerprint themselves
            if (path.size() == 1 && path[0] == "Scene")
              continue;
            // the friction tangent is a choice of how to solve too
            if (path.size() == 1 && path[0] == "Contact" &&
                (Utilities::trim(entry.substr(0, eq)) == "Friction tangent" ||
                 Utilities::trim(entry.substr(0, eq)) == "Geometric tangent"))
              continue;
            // so are the cut-backs (a failed run resumes with more), the
            // explicit step's fraction of the stable step and the number of
            // explicit steps (an unstable run or one that left the
            // quasi-static guard resumes with less or more; the step and the
            // mass are set anew at every station), the guard's limits, and
            // the size limit only guards the start
            const std::string name = Utilities::trim(entry.substr(0, eq));
            if (path.size() == 1 &&
                ((path[0] == "Time stepping" &&
                  Utilities::trim(entry.substr(0, eq)) ==
                    "Maximum cut-backs") ||
                 (path[0] == "Explicit" &&
                  (name == "Time step safety" || name == "Number of steps" ||
                   name == "Maximum kinetic energy ratio" ||
                   name == "Maximum force imbalance")) ||
                 (path[0] == "Mesh" &&
                  Utilities::trim(entry.substr(0, eq)) == "Maximum elements")))
              continue;
            for (const std::string &p : path)
              text << p << '/';
            text << Utilities::trim(entry.substr(0, eq)) << " = "
                 << (eq == std::string::npos ?
                       std::string() :
                       Utilities::trim(entry.substr(eq + 1)))
                 << '\n';
          }
      }
    return text.str();
  }



  void
  check_parameters(const Parameters &parameters)
  {
    {
      const std::string k =
        Utilities::trim(parameters.explicit_dynamics.contact_stiffness);
      bool valid = k == "auto";
      if (!valid)
        try
          {
            const double value = Utilities::string_to_double(k);
            valid              = value >= 1e-6 && value <= 100.;
          }
        catch (...)
          {}
      if (!valid)
        throw std::runtime_error(
          "Explicit/Contact stiffness = '" + k +
          "' is neither 'auto' nor a number from 1e-6 to 100; give e.g. 1 or "
          "auto");
    }
    for (const auto &[t, f] :
         parse_table(parameters.explicit_dynamics.step_profile,
                     "Explicit/Step profile"))
      if (!(f > 0. && f <= 1.))
        {
          std::ostringstream message;
          message << "Explicit/Step profile = '"
                  << parameters.explicit_dynamics.step_profile
                  << "': the factor " << f << " at " << t
                  << " s is not in (0, 1]; give factors above 0 and at most "
                     "1, e.g. '0:1, 0.78:1, 0.8:0.4'";
          throw std::runtime_error(message.str());
        }
    if (Utilities::trim(parameters.output.directory).empty())
      throw std::runtime_error(
        "Output/Directory is empty: give a directory for the results, e.g. "
        "'output' ('.' for the working directory)");
    // in MPa: beyond any solid (diamond: about 1.2e6 MPa), e.g. a value
    // given in Pa, which would make the contact penalty overflow
    if (parameters.material.youngs_modulus > 1e7)
      {
        std::ostringstream message;
        message << "Material/Young's modulus = "
                << parameters.material.youngs_modulus
                << " MPa is beyond any solid (diamond: 1.2e6 MPa); give it "
                   "in MPa (<= 1e7)";
        throw std::runtime_error(message.str());
      }
    for (const Point<3> &d : parse_points(parameters.mesh.refinement_directions,
                                          "Mesh/Refinement directions"))
      if (d.norm() == 0)
        throw std::runtime_error(
          "Mesh/Refinement directions: a direction must not be zero");
  }
} // namespace densify
