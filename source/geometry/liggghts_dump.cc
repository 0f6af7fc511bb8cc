// Reading the last snapshot of a LIGGGHTS (LAMMPS) text dump as particles,
// and moving the DEM contact overlaps of a bed apart.
#include <deal.II/base/utilities.h>

#include <densify/geometry/liggghts_dump.h>
#include <densify/geometry/number_field.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace densify
{
  namespace
  {
    /// Millimetres per metre: the dump is in SI units, Densify in mm.
    constexpr double mm_per_metre = 1000.;

    /// The most Jacobi sweeps of separate_overlaps().
    constexpr unsigned int max_sweeps = 100000;

    /// The fields of @p line separated by white space.
    std::vector<std::string>
    split_fields(const std::string &line)
    {
      std::istringstream       in(line);
      std::vector<std::string> fields;
      std::string              field;
      while (in >> field)
        fields.push_back(field);
      return fields;
    }



    /// Parse a whole field as an integer; false if it is not one.
    bool
    parse_integer(const std::string &field, long long &value)
    {
      if (field.empty())
        return false;
      char *end = nullptr;
      errno     = 0;
      value     = std::strtoll(field.c_str(), &end, 10);
      return end == field.c_str() + field.size() && errno == 0;
    }



    /// A number with at most 6 significant digits, for messages.
    std::string
    fmt(const double x)
    {
      std::ostringstream s;
      s.precision(6);
      s << x;
      return s.str();
    }



    /// Throw the one-line error "Particles/Particle file: WHERE: MESSAGE".
    [[noreturn]] void
    fail(const std::string &where, const std::string &message)
    {
      throw std::runtime_error("Particles/Particle file: " + where + ": " +
                               message);
    }



    /// Whether @p line is the item header @p item ("ITEM: ATOMS ...").
    bool
    is_item(const std::string &line, const std::string &item)
    {
      return line.compare(0, item.size(), item) == 0;
    }



    /**
     * Index pairs (i < j) of particles whose gap is below @p margin, in
     * lexicographic order. A grid of cells of the largest diameter plus the
     * margin: each particle is compared with those of the 27 cells around.
     */
    std::vector<std::pair<unsigned int, unsigned int>>
    close_pairs(const std::vector<Point<3>> &c,
                const std::vector<double>   &r,
                const double                 margin)
    {
      const unsigned int n     = c.size();
      double             r_max = 0;
      Point<3>           lower = c[0];
      for (unsigned int i = 0; i < n; ++i)
        {
          r_max = std::max(r_max, r[i]);
          for (unsigned int d = 0; d < 3; ++d)
            lower[d] = std::min(lower[d], c[i][d]);
        }
      const double cell = 2 * r_max + margin;
      using Key         = std::array<std::int64_t, 3>;
      auto key_of       = [&](const Point<3> &x) {
        Key key;
        for (unsigned int d = 0; d < 3; ++d)
          key[d] = static_cast<std::int64_t>(
            std::min(std::floor((x[d] - lower[d]) / cell), 1e15));
        return key;
      };
      std::vector<std::pair<Key, unsigned int>> bins(n);
      for (unsigned int i = 0; i < n; ++i)
        bins[i] = {key_of(c[i]), i};
      std::sort(bins.begin(), bins.end());

      std::vector<std::pair<unsigned int, unsigned int>> pairs;
      for (unsigned int i = 0; i < n; ++i)
        {
          const Key key = key_of(c[i]);
          for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dz = -1; dz <= 1; ++dz)
                {
                  const Key neighbour = {
                    {key[0] + dx, key[1] + dy, key[2] + dz}};
                  const auto range =
                    std::equal_range(bins.begin(),
                                     bins.end(),
                                     std::make_pair(neighbour, 0u),
                                     [](const auto &a, const auto &b) {
                                       return a.first < b.first;
                                     });
                  for (auto it = range.first; it != range.second; ++it)
                    {
                      const unsigned int j = it->second;
                      if (j > i && c[i].distance(c[j]) < r[i] + r[j] + margin)
                        pairs.emplace_back(i, j);
                    }
                }
        }
      std::sort(pairs.begin(), pairs.end());
      return pairs;
    }



    /// Put every particle inside the die and onto or above the lower punch.
    void
    clamp(std::vector<Point<3>>     &c,
          const std::vector<double> &r,
          const Container           &container)
    {
      for (unsigned int i = 0; i < c.size(); ++i)
        {
          if (container.has_lower && c[i][2] - r[i] < container.lower_z)
            c[i][2] = container.lower_z + r[i];
          const double rho = std::sqrt(c[i][0] * c[i][0] + c[i][1] * c[i][1]);
          if (container.has_die && rho + r[i] > container.die_radius)
            {
              const double scale = (container.die_radius - r[i]) / rho;
              c[i][0] *= scale;
              c[i][1] *= scale;
            }
        }
    }
  } // namespace



  bool
  is_liggghts_dump(const std::string &filename)
  {
    std::ifstream in(filename);
    std::string   line;
    while (in && std::getline(in, line))
      {
        const std::string text = Utilities::trim(line);
        if (!text.empty())
          return is_item(text, "ITEM:");
      }
    return false;
  }



  std::vector<Particle>
  read_liggghts_dump(const std::string &filename, const std::string &materials)
  {
    errno = 0;
    std::ifstream in(filename);
    if (!in)
      {
        const int error = errno;
        fail("cannot open '" + filename + "'",
             error != 0 ? std::strerror(error) : "unknown error");
      }

    // the last snapshot: where its "ITEM: TIMESTEP" line starts
    std::string    line;
    std::streampos start       = 0;
    unsigned int   start_line  = 0;
    unsigned int   line_number = 0;
    std::streampos line_start  = in.tellg();
    while (std::getline(in, line))
      {
        ++line_number;
        if (Utilities::trim(line) == "ITEM: TIMESTEP")
          {
            start      = line_start;
            start_line = line_number;
          }
        line_start = in.tellg();
      }
    if (in.bad())
      fail(filename, "error while reading");
    if (start_line == 0)
      fail(filename,
           "no 'ITEM: TIMESTEP' line: not a LIGGGHTS/LAMMPS text dump "
           "(dump ID all custom N FILE id type x y z radius), nor a CSV file "
           "x,y,z,diameter[,material]");
    in.clear();
    in.seekg(start);
    line_number = start_line - 1;
    auto next   = [&](std::string &text) {
      if (!std::getline(in, text))
        return false;
      ++line_number;
      text = Utilities::trim(text);
      return true;
    };
    auto where = [&]() { return filename + ":" + std::to_string(line_number); };

    std::string timestep = "?";
    long long   n_atoms  = -1;
    std::string header;
    next(line); // ITEM: TIMESTEP
    if (next(line) && !is_item(line, "ITEM:"))
      timestep = line;
    bool found_atoms = is_item(line, "ITEM: ATOMS");
    while (!found_atoms && next(line))
      {
        if (line == "ITEM: NUMBER OF ATOMS")
          {
            if (!next(line) || !parse_integer(line, n_atoms) || n_atoms < 0)
              fail(where(),
                   "'ITEM: NUMBER OF ATOMS' is not followed by a count >= 0: "
                   "the dump is damaged; write it again");
          }
        else if (is_item(line, "ITEM: ATOMS"))
          found_atoms = true;
      }
    const std::string snapshot = "the last snapshot (timestep " + timestep +
                                 ", line " + std::to_string(start_line) + ")";
    if (!found_atoms)
      fail(filename,
           snapshot +
             " has no 'ITEM: ATOMS' block: the dump is cut short or not a "
             "'dump custom' of LIGGGHTS (dump ID all custom N FILE id type x y "
             "z radius)");
    if (n_atoms < 0)
      fail(where(),
           snapshot + " has no 'ITEM: NUMBER OF ATOMS' before its atoms: the "
                      "dump is damaged; write it again");
    if (n_atoms == 0)
      fail(where(),
           snapshot +
             " has no atoms: point Particles/Particle file at the dump of a "
             "filled die");

    // the columns, by their names on the ATOMS line
    const unsigned int             atoms_line = line_number;
    const std::vector<std::string> columns    = split_fields(line.substr(11));
    auto column = [&](const std::vector<std::string> &names) {
      for (const std::string &name : names)
        {
          const auto it = std::find(columns.begin(), columns.end(), name);
          if (it != columns.end())
            return static_cast<int>(it - columns.begin());
        }
      return -1;
    };
    const int k_id   = column({"id"});
    const int k_type = column({"type"});
    const int k_x[3] = {column({"x", "xu"}),
                        column({"y", "yu"}),
                        column({"z", "zu"})};
    const int k_r    = column({"radius"});
    const int k_d    = column({"diameter"});
    for (unsigned int d = 0; d < 3; ++d)
      if (k_x[d] < 0)
        {
          const std::string axis(1, "xyz"[d]);
          fail(where(),
               column({axis + "s", axis + "su"}) >= 0 ?
                 "scaled coordinates (" + axis +
                   "s) are not read: dump the coordinates x y z "
                   "(dump ID all custom N FILE id type x y z radius)" :
                 "the ATOMS line has no column " + axis +
                   ": dump the coordinates x y z "
                   "(dump ID all custom N FILE id type x y z radius)");
        }
    if (k_r < 0 && k_d < 0)
      fail(where(),
           "the ATOMS line has no column radius (or diameter): add it to the "
           "dump (dump ID all custom N FILE id type x y z radius)");

    std::vector<std::string> names;
    for (const std::string &name : split_fields([&] {
           std::string list = materials;
           std::replace(list.begin(), list.end(), ',', ' ');
           return list;
         }()))
      names.push_back(name);
    if (names.empty())
      names.push_back("Sn");

    // the atoms, with their ids and the lines they are on
    struct Atom
    {
      long long    id;
      unsigned int line;
      Particle     particle;
    };
    std::vector<Atom> atoms;
    atoms.reserve(n_atoms);
    for (long long a = 0; a < n_atoms; ++a)
      {
        if (!next(line) || is_item(line, "ITEM:"))
          fail(where(),
               snapshot + " ends after " + std::to_string(a) + " of " +
                 std::to_string(n_atoms) +
                 " atoms: the dump is cut short (LIGGGHTS still writing?); "
                 "use a complete dump");
        const std::vector<std::string> fields = split_fields(line);
        if (fields.size() < columns.size())
          fail(where(),
               "expected " + std::to_string(columns.size()) +
                 " fields as named on line " + std::to_string(atoms_line) +
                 ", got " + std::to_string(fields.size()) +
                 ": the dump is damaged; write it again");
        auto number = [&](const int k) {
          double value = 0;
          if (!parse_number(fields[k], value))
            fail(where(),
                 "field " + std::to_string(k + 1) + " (" + columns[k] + ") '" +
                   fields[k] +
                   "' is not a number: the dump is damaged; write it again");
          return value;
        };
        Atom atom;
        atom.line = line_number;
        atom.id   = a + 1;
        if (k_id >= 0 && !parse_integer(fields[k_id], atom.id))
          fail(where(),
               "field " + std::to_string(k_id + 1) + " (id) '" + fields[k_id] +
                 "' is not an integer: the dump is damaged; write it again");
        long long type = 1;
        if (k_type >= 0 && (!parse_integer(fields[k_type], type) || type < 1))
          fail(where(),
               "field " + std::to_string(k_type + 1) + " (type) '" +
                 fields[k_type] +
                 "' is not an atom type >= 1: the dump is damaged; write it "
                 "again");
        for (unsigned int d = 0; d < 3; ++d)
          atom.particle.centre[d] = mm_per_metre * number(k_x[d]);
        const double radius = k_r >= 0 ? number(k_r) : number(k_d) / 2;
        if (!(radius > 0))
          fail(where(),
               "atom " + std::to_string(atom.id) + " has the radius " +
                 fmt(radius) +
                 " m: radii must be > 0; dump the settled bed of a fill "
                 "(id type x y z radius)");
        atom.particle.diameter = 2 * mm_per_metre * radius;
        if (names.size() == 1)
          atom.particle.material = names[0];
        else if (static_cast<std::size_t>(type) <= names.size())
          atom.particle.material = names[type - 1];
        else
          throw std::runtime_error(
            "Particles/Materials: " + where() + ": atom " +
            std::to_string(atom.id) + " has the type " + std::to_string(type) +
            ", but '" + materials + "' names " + std::to_string(names.size()) +
            " materials: give one name per atom type, type 1 first");
        atoms.push_back(atom);
      }

    std::stable_sort(atoms.begin(),
                     atoms.end(),
                     [](const auto &a, const auto &b) { return a.id < b.id; });
    std::vector<Particle> particles;
    particles.reserve(atoms.size());
    for (unsigned int i = 0; i < atoms.size(); ++i)
      {
        if (i > 0 && atoms[i].id == atoms[i - 1].id)
          fail(filename + ":" + std::to_string(atoms[i].line),
               "atom " + std::to_string(atoms[i].id) + " appears twice in " +
                 snapshot + " (also on line " +
                 std::to_string(atoms[i - 1].line) +
                 "): the dump is damaged; write it again");
        particles.push_back(atoms[i].particle);
      }
    return particles;
  }



  OverlapSeparation
  separate_overlaps(std::vector<Particle> &particles,
                    const Container       &container,
                    const std::string     &what,
                    const double           limit)
  {
    OverlapSeparation  result;
    const unsigned int n = particles.size();
    if (n == 0)
      return result;
    std::vector<Point<3>> c(n);
    std::vector<double>   r(n);
    double                d_min = std::numeric_limits<double>::max();
    for (unsigned int i = 0; i < n; ++i)
      {
        c[i]  = particles[i].centre;
        r[i]  = particles[i].diameter / 2;
        d_min = std::min(d_min, particles[i].diameter);
      }
    const double gap    = 1e-6 * d_min;
    const double margin = 0.1 * d_min;

    // the largest overlap, and what to say if it is too large for a DEM bed
    double      worst = 0;
    std::string problem, fix;
    auto        percent = [](const double fraction) {
      return fmt(100 * fraction) + " %";
    };
    for (unsigned int i = 0; i < n; ++i)
      {
        const std::string name = "particle " + std::to_string(i);
        if (container.has_die)
          {
            const double excess =
              std::hypot(c[i][0], c[i][1]) + r[i] - container.die_radius;
            if (excess / (2 * r[i]) > worst)
              {
                worst   = excess / (2 * r[i]);
                problem = name + " crosses the die wall by " + fmt(excess) +
                          " mm, " + percent(worst) + " of its diameter";
                fix = "set Tools/Die wall/Diameter to the die of the fill, "
                      "whose axis must lie on x = y = 0 (the dump in metres)";
              }
          }
        if (container.has_lower)
          {
            const double excess = container.lower_z - (c[i][2] - r[i]);
            if (excess / (2 * r[i]) > worst)
              {
                worst   = excess / (2 * r[i]);
                problem = name + " reaches " + fmt(excess) +
                          " mm below the lower punch, " + percent(worst) +
                          " of its diameter";
                fix = "set Tools/Lower punch/Position to the floor of the "
                      "fill (the dump in metres)";
              }
          }
      }
    std::vector<std::pair<unsigned int, unsigned int>> pairs =
      close_pairs(c, r, margin);
    for (const auto &[i, j] : pairs)
      {
        const double overlap = r[i] + r[j] - c[i].distance(c[j]);
        if (overlap / (2 * std::min(r[i], r[j])) > worst)
          {
            worst   = overlap / (2 * std::min(r[i], r[j]));
            problem = "particles " + std::to_string(i) + " and " +
                      std::to_string(j) + " overlap by " + fmt(overlap) +
                      " mm, " + percent(worst) + " of the smaller diameter";
            fix = "is the dump in metres (LIGGGHTS' units si)?";
          }
      }
    result.largest_overlap = worst;
    if (worst > limit)
      throw std::runtime_error(what + ": " + problem +
                               ", more than DEM contacts overlap (at most " +
                               percent(limit) + "): " + fix);

    // Jacobi sweeps
    const std::vector<Point<3>> start = c;
    std::vector<Point<3>>       built = c;
    clamp(c, r, container);
    std::vector<Tensor<1, 3>> shift(n), halves;
    unsigned int              sweep = 0;
    for (; sweep < max_sweeps; ++sweep)
      {
        double moved = 0;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            moved = std::max(moved, std::abs(c[i][d] - built[i][d]));
        if (moved > margin / 2)
          {
            pairs = close_pairs(c, r, margin);
            built = c;
          }
        double overlap = -std::numeric_limits<double>::max();
        for (const auto &[i, j] : pairs)
          overlap = std::max(overlap, r[i] + r[j] - c[i].distance(c[j]));
        if (pairs.empty() || overlap <= 0)
          break;
        // the pushes, summed in the order the script sums them (the
        // first particles of the pairs, then the second ones)
        std::fill(shift.begin(), shift.end(), Tensor<1, 3>());
        halves.clear();
        for (const auto &[i, j] : pairs)
          {
            const Tensor<1, 3> v    = c[j] - c[i];
            const double       dist = v.norm();
            const double       push = r[i] + r[j] + gap - dist;
            halves.push_back(push > 0 ? (0.5 * push / dist) * v :
                                        Tensor<1, 3>());
          }
        for (unsigned int k = 0; k < pairs.size(); ++k)
          shift[pairs[k].first] -= halves[k];
        for (unsigned int k = 0; k < pairs.size(); ++k)
          shift[pairs[k].second] += halves[k];
        for (unsigned int i = 0; i < n; ++i)
          c[i] += shift[i];
        clamp(c, r, container);
      }
    if (sweep == max_sweeps)
      throw std::runtime_error(what +
                               ": the overlapping particles could not be "
                               "moved apart in " +
                               std::to_string(max_sweeps) + " sweeps");

    result.sweeps = sweep;
    for (unsigned int i = 0; i < n; ++i)
      {
        result.largest_shift =
          std::max(result.largest_shift, start[i].distance(c[i]));
        particles[i].centre = c[i];
      }
    return result;
  }
} // namespace densify
