// The scene of a run as read from the parameters: particles, tool positions,
// load history.
#include <deal.II/base/utilities.h>

#include <densify/geometry/deposition.h>
#include <densify/geometry/liggghts_dump.h>
#include <densify/geometry/packing.h>
#include <densify/geometry/particle_shape.h>
#include <densify/material/factory.h>
#include <densify/scene.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    /// A punch's target force tables, one per force window (separated by
    /// ';'), from Tools/@p punch/Force history or Pressure history (empty if
    /// neither is given), with its @p tolerance and @p max_speed checked.
    std::vector<std::vector<std::pair<double, double>>>
    force_table(const Parameters  &prm,
                const std::string &punch,
                const std::string &force,
                const std::string &pressure,
                const double       tolerance,
                const double       max_speed)
    {
      const std::string prefix      = "Tools/" + punch + "/";
      const bool        by_force    = !Utilities::trim(force).empty();
      const bool        by_pressure = !Utilities::trim(pressure).empty();
      if (by_force && by_pressure)
        throw std::runtime_error(prefix +
                                 "Pressure history: give either it or Force "
                                 "history, not both");
      if (!by_force && !by_pressure)
        return {};
      if (by_pressure && !prm.tools.die_enabled)
        throw std::runtime_error(
          prefix +
          "Pressure history: a mean stress needs the die's bore (Tools/Die "
          "wall/Enabled = true); give a Force history instead");
      const std::string what =
        prefix + (by_force ? "Force history" : "Pressure history");
      std::vector<std::vector<std::pair<double, double>>> windows;
      for (const std::string &text :
           Utilities::split_string_list(by_force ? force : pressure, ';'))
        {
          windows.push_back(parse_table(text, what));
          auto &table = windows.back();
          if (table.size() < 2)
            throw std::runtime_error(
              what + ": give at least two pairs in each window (the force "
                     "control acts between its first time and its last)");
          if (windows.size() > 1 && !(table.front().first >=
                                      windows[windows.size() - 2].back().first))
            throw std::runtime_error(
              what + ": the window '" + text +
              "' starts before the one before it ends; give the windows "
              "(separated by ';') in time order");
          for (auto &[t, value] : table)
            {
              if (t < 0. || t > prm.time.end_time)
                throw std::runtime_error(
                  what + ": the time " + std::to_string(t) +
                  " s lies outside [0, Time stepping/End time]; give times "
                  "within the run");
              if (value < 0.)
                throw std::runtime_error(
                  what + ": " + std::to_string(value) +
                  " is negative; give compressive values (>= 0)");
              if (by_pressure)
                value *= numbers::PI / 4. * prm.tools.die_diameter *
                         prm.tools.die_diameter;
            }
        }
      if (!(max_speed >= 0.))
        throw std::runtime_error(
          prefix + "Maximum speed: give a speed >= 0 (mm/s; 0 takes the "
                   "displacement history's)");
      if (!(tolerance > 0.))
        throw std::runtime_error(prefix +
                                 "Force tolerance: give a positive relative "
                                 "tolerance (e.g. 1e-3)");
      return windows;
    }


    /// Refuses an upper punch history that reaches the lower punch, or that
    /// would press the spheres' volume past the die's (relative density
    /// above 100 %), before anything is meshed.
    void
    check_stroke(const Scene                 &scene,
                 const Parameters            &prm,
                 const std::vector<Particle> &particles)
    {
      // the tables are piecewise linear: the punches come closest in
      // [0, End time] at a breakpoint of either or at the end time; the
      // stroke is the travel that takes them there (the lower punch's rise
      // counts as stroke). Once a punch is under force control, the
      // displacement histories go on from where it left them: the force
      // control itself stops a punch that would meet the other.
      double end = prm.time.end_time;
      for (const auto *windows : {&scene.force_table, &scene.lower_force_table})
        if (!windows->empty())
          end = std::min(end, windows->front().front().first);
      std::vector<double> times(1, end);
      for (const auto *table : {&scene.punch_table, &scene.lower_table})
        for (const auto &[t, v] : *table)
          if (t <= end)
            times.push_back(t);
      double stroke = 0.;
      for (const double t : times)
        stroke = std::max(stroke,
                          interpolate(scene.punch_table, t) +
                            interpolate(scene.lower_table, t));
      const double       gap = scene.upper_initial - prm.tools.lower_position;
      std::ostringstream message;
      message << "Tools/Upper punch/Displacement history: ";
      if (stroke >= gap)
        {
          message << "the stroke of " << stroke
                  << " mm reaches the lower punch " << gap
                  << " mm below the upper one: give a stroke below the gap "
                     "(or stop earlier with Time stepping/End time)";
          throw std::runtime_error(message.str());
        }
      if (!prm.tools.die_enabled)
        return;
      const double density =
        layer_relative_density(particles, prm.tools.die_diameter, gap - stroke);
      if (density > 1.)
        {
          message << "the stroke of " << stroke
                  << " mm would press the spheres to " << std::fixed
                  << std::setprecision(1) << 100. * density
                  << " % relative density (the die holds at most 100 %): "
                     "give a shorter stroke";
          throw std::runtime_error(message.str());
        }
    }
  } // namespace



  void
  draw_materials(const std::string     &fractions,
                 const unsigned int     seed,
                 std::vector<Particle> &particles)
  {
    const std::string what = "Particles/Material fractions";
    std::vector<std::pair<std::string, double>> mixture;
    double                                      sum = 0;
    for (const std::string &item : Utilities::split_string_list(fractions, ','))
      {
        const std::vector<std::string> parts =
          Utilities::split_string_list(item, ':');
        double f = -1;
        if (parts.size() == 2)
          try
            {
              f = Utilities::string_to_double(parts[1]);
            }
          catch (...)
            {}
        if (!(f >= 0))
          throw std::runtime_error(what + ": '" + item +
                                   "' is not 'name:fraction' with a fraction "
                                   ">= 0");
        mixture.emplace_back(parts[0], f);
        sum += f;
      }
    if (std::abs(sum - 1) > 1e-6)
      throw std::runtime_error(what + ": the fractions add up to " +
                               std::to_string(sum) + ", not 1");
    // whole particles per material: floor, then the largest remainders
    const unsigned int        n = particles.size();
    std::vector<unsigned int> count(mixture.size());
    std::vector<unsigned int> order(mixture.size());
    unsigned int              given = 0;
    for (unsigned int k = 0; k < mixture.size(); ++k)
      {
        count[k] = static_cast<unsigned int>(std::floor(mixture[k].second * n));
        given += count[k];
        order[k] = k;
      }
    std::stable_sort(order.begin(), order.end(), [&](unsigned a, unsigned b) {
      return mixture[a].second * n - count[a] >
             mixture[b].second * n - count[b];
    });
    for (unsigned int k = 0; given < n; ++k, ++given)
      ++count[order[k % order.size()]];
    // which particle gets which: a seeded shuffle
    std::vector<unsigned int> index(n);
    std::iota(index.begin(), index.end(), 0u);
    std::mt19937 generator(seed);
    for (unsigned int i = n; i > 1; --i)
      std::swap(index[i - 1],
                index[std::uniform_int_distribution<unsigned int>(0, i - 1)(
                  generator)]);
    unsigned int next = 0;
    for (unsigned int k = 0; k < mixture.size(); ++k)
      for (unsigned int c = 0; c < count[k]; ++c)
        particles[index[next++]].material = mixture[k].first;
  }



  namespace
  {
    /// What Particles/Packing = deposited pours, from the parameters and
    /// the fields of Particles/Diameters.
    DepositionSpec
    deposition_spec(const Parameters               &prm,
                    const std::vector<std::string> &diameters,
                    const std::string              &material)
    {
      const ParticleParameters &pp = prm.particles;
      DepositionSpec            spec;
      spec.die_diameter = prm.tools.die_diameter;
      spec.floor        = prm.tools.lower_position;
      spec.n_particles  = pp.n_particles;
      spec.fill_height  = pp.fill_height;
      spec.seed         = pp.packing_seed;
      spec.material     = material;
      spec.first        = Utilities::string_to_double(diameters.at(0));
      if (pp.size_distribution == "uniform")
        {
          if (diameters.size() != 2)
            throw std::runtime_error(
              "Particles/Size distribution = uniform needs Particles/"
              "Diameters = 'dmin, dmax', not '" +
              pp.diameters + "'");
          spec.sizes  = SizeDistribution::uniform;
          spec.second = Utilities::string_to_double(diameters[1]);
        }
      else if (pp.size_distribution == "log-normal")
        {
          spec.sizes  = SizeDistribution::log_normal;
          spec.second = pp.diameter_spread;
        }
      return spec;
    }
  } // namespace



  Scene
  build_scene(const Parameters &prm)
  {
    Scene                     scene;
    std::vector<Particle>    &particles = scene.particles;
    const ParticleParameters &pp        = prm.particles;
    if (pp.packing != "list")
      {
        if (!prm.tools.die_enabled || !prm.tools.lower_enabled)
          throw std::runtime_error(
            "Particles/Packing = " + pp.packing +
            " fills the die on the lower punch: enable Tools/Die wall and "
            "Tools/Lower punch, or set Particles/Packing = list");
        const std::vector<std::string> d_list =
          Utilities::split_string_list(pp.diameters, ',');
        double d = 0;
        try
          {
            d = Utilities::string_to_double(d_list.at(0));
          }
        catch (...)
          {
            throw std::runtime_error("Particles/Diameters: '" + pp.diameters +
                                     "' does not start with a number");
          }
        if (!(d > 0))
          throw std::runtime_error(
            "Particles/Diameters: the layer's diameter must be > 0 mm");
        const std::vector<std::string> m_list =
          Utilities::split_string_list(pp.materials, ',');
        for (const std::string &m : m_list)
          if (m != m_list.at(0))
            throw std::runtime_error(
              "Particles/Materials: a " + pp.packing +
              " has one material, not the list '" + pp.materials +
              "': give one name, or a mixture in Particles/Material "
              "fractions");
        const std::string material = m_list.at(0);
        const double      z        = prm.tools.lower_position + d / 2;
        try
          {
            if (pp.packing == "hexagonal layer")
              {
                const std::string       &where = pp.hexagonal_placement;
                const HexagonalPlacement placement =
                  where == "particle centred" ?
                    HexagonalPlacement::particle_centred :
                  where == "hole centred" ? HexagonalPlacement::hole_centred :
                  where == "edge centred" ? HexagonalPlacement::edge_centred :
                                            HexagonalPlacement::best;
                particles = hexagonal_layer(
                  prm.tools.die_diameter, d, z, material, 0., placement);
              }
            else if (pp.packing == "deposited")
              particles = deposit(deposition_spec(prm, d_list, material));
            else
              particles = random_layer(prm.tools.die_diameter,
                                       d,
                                       z,
                                       pp.n_particles,
                                       pp.packing_seed,
                                       material);
          }
        catch (const std::exception &e)
          {
            throw std::runtime_error(
              "Particles/Packing = " + pp.packing + ": " + e.what() +
              " (Particles/Number of particles, Particles/Diameters)");
          }
        if (particles.empty())
          throw std::runtime_error(
            "Particles/Packing = " + pp.packing + ": no sphere of diameter " +
            d_list.at(0) +
            " mm fits the die: lower Particles/Diameters or widen Tools/Die "
            "wall/Diameter");
      }
    else if (!pp.particle_file.empty())
      {
        particles =
          read_particle_csv(pp.particle_file, pp.materials, pp.packing_seed);
        // a DEM bed (LIGGGHTS dump): its soft contacts overlap a little;
        // moved apart in the die and on the lower punch
        if (is_liggghts_dump(pp.particle_file))
          {
            Container die;
            die.has_die    = prm.tools.die_enabled;
            die.die_radius = prm.tools.die_diameter / 2;
            die.has_lower  = prm.tools.lower_enabled;
            die.lower_z    = prm.tools.lower_position;
            separate_overlaps(particles,
                              die,
                              "Particles/Particle file: '" + pp.particle_file +
                                "' (a LIGGGHTS dump)");
          }
      }
    else
      {
        const std::vector<Point<3>> centres =
          parse_points(pp.centres, "Particles/Centres");
        const std::vector<std::string> d_list =
          Utilities::split_string_list(pp.diameters, ',');
        const std::vector<std::string> m_list =
          Utilities::split_string_list(pp.materials, ',');
        if (d_list.size() != 1 && d_list.size() != centres.size())
          throw std::runtime_error(
            "Particles/Diameters: give one value or one per centre (" +
            std::to_string(centres.size()) + "), not " +
            std::to_string(d_list.size()));
        if (m_list.size() != 1 && m_list.size() != centres.size())
          throw std::runtime_error(
            "Particles/Materials: give one name or one per centre (" +
            std::to_string(centres.size()) + "), not " +
            std::to_string(m_list.size()));
        for (unsigned int i = 0; i < centres.size(); ++i)
          {
            Particle p;
            p.centre             = centres[i];
            const std::string &d = d_list[d_list.size() == 1 ? 0 : i];
            try
              {
                p.diameter = Utilities::string_to_double(d);
              }
            catch (...)
              {
                throw std::runtime_error("Particles/Diameters: '" + d +
                                         "' is not a number");
              }
            p.material = m_list[m_list.size() == 1 ? 0 : i];
            particles.push_back(p);
          }
      }
    if (particles.empty())
      throw std::runtime_error(
        "no particles: set Particles/Centres or Particles/Particle file");
    if (!pp.material_fractions.empty())
      draw_materials(pp.material_fractions, pp.material_seed, particles);

    // before any use of the diameters (the punch's start below)
    for (unsigned int i = 0; i < particles.size(); ++i)
      if (!(particles[i].diameter > 0) || !std::isfinite(particles[i].diameter))
        throw std::runtime_error(
          "particle " + std::to_string(i) + ": diameter " +
          Utilities::to_string(particles[i].diameter) +
          " mm must be a number > 0 (Particles/Diameters or the particle "
          "file)");

    // the upper punch starts on the highest particle unless told otherwise
    double top = -std::numeric_limits<double>::max();
    for (const Particle &p : particles)
      top = std::max(top, p.centre[2] + support(p, Point<3>(0., 0., 1.)));
    const std::string &init = prm.tools.upper_initial_position;
    if (init == "auto")
      scene.upper_initial = top;
    else
      try
        {
          scene.upper_initial = Utilities::string_to_double(init);
        }
      catch (...)
        {
          throw std::runtime_error("Tools/Upper punch/Initial position: '" +
                                   init + "' is neither a number nor 'auto'");
        }
    scene.punch_table       = parse_table(prm.tools.upper_displacement,
                                    "Tools/Upper punch/Displacement history");
    scene.force_table       = force_table(prm,
                                    "Upper punch",
                                    prm.tools.upper_force,
                                    prm.tools.upper_pressure,
                                    prm.tools.force_tolerance,
                                    prm.tools.max_speed);
    scene.lower_force_table = force_table(prm,
                                          "Lower punch",
                                          prm.tools.lower_force,
                                          prm.tools.lower_pressure,
                                          prm.tools.lower_force_tolerance,
                                          prm.tools.lower_max_speed);

    {
      const std::vector<Point<3>> b =
        parse_points(prm.particles.body_force, "Particles/Body force");
      if (b.size() != 1)
        throw std::runtime_error(
          "Particles/Body force: give one vector 'bx,by,bz' (N/mm^3)");
      scene.body_force       = b[0];
      scene.body_force_table = parse_table(prm.particles.body_force_history,
                                           "Particles/Body force history");
    }
    scene.lateral_table =
      parse_table(prm.tools.upper_lateral_displacement,
                  "Tools/Upper punch/Lateral displacement history");
    scene.lower_table = parse_table(prm.tools.lower_displacement,
                                    "Tools/Lower punch/Displacement history");
    scene.die_table   = parse_table(prm.tools.die_displacement,
                                  "Tools/Die wall/Displacement history");
    if (prm.tools.die_top != "none")
      {
        double die_top = std::numeric_limits<double>::quiet_NaN();
        try
          {
            die_top = Utilities::string_to_double(prm.tools.die_top);
          }
        catch (...)
          {}
        if (!std::isfinite(die_top) ||
            (prm.tools.lower_enabled && !(die_top > prm.tools.lower_position)))
          throw std::runtime_error(
            "Tools/Die wall/Top: '" + prm.tools.die_top +
            "' is not a height above the lower punch (Tools/Lower "
            "punch/Position = " +
            Utilities::to_string(prm.tools.lower_position) +
            " mm): give one, or 'none' for a die without end");
        scene.die_top = die_top;
      }

    Container container;
    container.has_die    = prm.tools.die_enabled;
    container.die_radius = prm.tools.die_diameter / 2;
    container.has_lower  = prm.tools.lower_enabled;
    container.lower_z    = prm.tools.lower_position;
    container.has_upper  = prm.tools.upper_enabled;
    container.upper_z    = scene.upper_initial;
    if (container.has_lower && container.has_upper &&
        !(scene.upper_initial > prm.tools.lower_position))
      throw std::runtime_error(
        "Tools/Upper punch/Initial position must be above Tools/Lower "
        "punch/Position");
    check_particles(particles, container, 1e-9 * top);
    if (container.has_lower && container.has_upper)
      check_stroke(scene, prm, particles);

    // unknown material names are input errors too
    for (const Particle &p : particles)
      create_material(p.material, prm.material);
    return scene;
  }



  MeshEstimate
  estimate_mesh(const Parameters &prm, const std::vector<Particle> &particles)
  {
    // tetrahedra per volume of a mesh of size h: about 5.9 / h^3 (gmsh:
    // 1795 tetrahedra in a sphere of diameter 2.5 mm with h = 0.3 mm)
    constexpr double density      = 5.9;
    const double     H            = prm.mesh.element_size;
    const double     h_r          = std::min(prm.mesh.refined_element_size, H);
    const double     g            = prm.mesh.growth;
    unsigned int     n_directions = 0;
    try
      {
        n_directions = parse_points(prm.mesh.refinement_directions,
                                    "Mesh/Refinement directions")
                         .size();
      }
    catch (...)
      {
        // reported where the mesh is built
      }
    MeshEstimate             estimate;
    std::map<double, double> per_diameter;
    unsigned int             n_shaped = 0;
    for (const Particle &p : particles)
      {
        // spheres by diameter; every other shape by itself (a key of its
        // own below zero)
        const double key =
          p.shape == ParticleShape::sphere ? p.diameter : -1. - n_shaped++;
        auto it = per_diameter.find(key);
        if (it == per_diameter.end())
          {
            const double r      = p.diameter / 2;
            const double volume = particle_volume(p);
            double       n      = density * volume / (H * H * H);
            if (n_directions > 0 && h_r < H)
              {
                // each refinement point: the elements of h(d) = h_r + g d
                // in a half ball around it, beyond those of size H
                const double       reach = std::min((H - h_r) / g, 2 * r);
                const unsigned int k     = 200;
                double             extra = 0;
                for (unsigned int i = 0; i < k; ++i)
                  {
                    const double d  = (i + 0.5) * reach / k;
                    const double hd = h_r + g * d;
                    extra += 2 * numbers::PI * d * d * reach / k * density *
                             (1 / (hd * hd * hd) - 1 / (H * H * H));
                  }
                n = std::min(n + n_directions * extra,
                             density * volume / (h_r * h_r * h_r));
              }
            it = per_diameter.emplace(key, n).first;
          }
        estimate.elements += it->second;
      }
    estimate.distinct_diameters = per_diameter.size();
    // measured peaks of whole runs (mesh, matrix, AMG, history) per element
    estimate.bytes =
      estimate.elements * (prm.mesh.degree == 1 ? 4e3 : 2e4) + 2e8;
    return estimate;
  }



  std::string
  format_count(const double n)
  {
    std::ostringstream text;
    if (n < 10 && n != std::round(n))
      text << std::fixed << std::setprecision(1) << n;
    else if (n < 1e12)
      text << std::llround(n);
    else
      text << std::setprecision(2) << n;
    return text.str();
  }



  void
  check_mesh_size(const Parameters &prm, const MeshEstimate &estimate)
  {
    if (estimate.elements > prm.mesh.max_elements)
      {
        std::ostringstream message;
        message << "the scene needs about " << format_count(estimate.elements)
                << " tetrahedra (about " << format_count(estimate.bytes / 1e9)
                << " GB of memory), more than Mesh/Maximum elements = "
                << prm.mesh.max_elements
                << ": raise Mesh/Element size (the count grows as its "
                   "inverse cube) or Mesh/Refined element size, use fewer "
                   "particles, or raise Mesh/Maximum elements on a machine "
                   "with that memory";
        throw std::runtime_error(message.str());
      }
  }



  void
  check_element_size(const Parameters            &prm,
                     const std::vector<Particle> &particles)
  {
    double smallest = std::numeric_limits<double>::max();
    for (const Particle &p : particles)
      smallest = std::min(smallest, smallest_width(p));
    if (prm.mesh.element_size > smallest)
      {
        std::ostringstream message;
        message << "Mesh/Element size = " << prm.mesh.element_size
                << " mm is larger than the smallest particle (diameter or "
                   "smallest width "
                << smallest << " mm), which cannot be meshed with it: give "
                << "at most " << smallest << " mm (a fifth of it, "
                << smallest / 5 << " mm, for a usable answer)";
        throw std::runtime_error(message.str());
      }
  }
} // namespace densify
