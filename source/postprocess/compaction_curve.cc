// Punch stresses, die wall pressure, and the Heckel and Kawakita fits.
#include <densify/postprocess/compaction_curve.h>
#include <densify/postprocess/statistics.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace densify
{
  namespace
  {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    constexpr double pi  = 3.14159265358979323846;

    /// The comma-separated fields of @p line.
    std::vector<std::string>
    fields(const std::string &line)
    {
      std::vector<std::string> result;
      std::istringstream       in(line);
      for (std::string f; std::getline(in, f, ',');)
        result.push_back(f);
      return result;
    }



    /// The largest finite entry of @p v (0 if none is positive).
    double
    largest_value(const std::vector<double> &v)
    {
      double largest = 0;
      for (const double x : v)
        if (std::isfinite(x))
          largest = std::max(largest, x);
      return largest;
    }
  } // namespace



  DieStresses
  die_stresses(const double upper_force,
               const double lower_force,
               const double die_radial_force,
               const double die_diameter,
               const double punch_gap)
  {
    DieStresses s;
    if (!(die_diameter > 0))
      {
        s.upper_punch = s.lower_punch = s.die_wall = s.radial_axial_ratio = nan;
        return s;
      }
    const double bore = pi * die_diameter * die_diameter / 4;
    s.upper_punch     = upper_force / bore;
    s.lower_punch     = lower_force / bore;
    s.die_wall =
      punch_gap > 0 ? die_radial_force / (pi * die_diameter * punch_gap) : nan;
    // no axial stress, no ratio to speak of: 0 (NaN only where a tool is
    // missing)
    s.radial_axial_ratio = s.upper_punch > 0 ? s.die_wall / s.upper_punch : 0.;
    return s;
  }



  LineFit
  fit_line(const std::vector<double> &x, const std::vector<double> &y)
  {
    LineFit           fit;
    const std::size_t n = std::min(x.size(), y.size());
    fit.slope = fit.intercept = fit.r_squared = nan;
    if (n < 2)
      return fit;
    // centred sums: no cancellation for points far from the origin
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < n; ++i)
      {
        mx += x[i];
        my += y[i];
      }
    mx /= n;
    my /= n;
    double sxx = 0, sxy = 0, syy = 0;
    for (std::size_t i = 0; i < n; ++i)
      {
        sxx += (x[i] - mx) * (x[i] - mx);
        sxy += (x[i] - mx) * (y[i] - my);
        syy += (y[i] - my) * (y[i] - my);
      }
    if (!(sxx > 0))
      return fit;
    fit.points    = n;
    fit.slope     = sxy / sxx;
    fit.intercept = my - fit.slope * mx;
    fit.r_squared = syy > 0 ? sxy * sxy / (sxx * syy) : 1.;
    return fit;
  }



  LineFit
  fit_heckel(const std::vector<double> &P,
             const std::vector<double> &D,
             const double               min_pressure_fraction)
  {
    const double        smallest = min_pressure_fraction * largest_value(P);
    std::vector<double> x, y;
    for (std::size_t i = 0; i < std::min(P.size(), D.size()); ++i)
      if (P[i] > 0 && P[i] >= smallest && D[i] > 0 && D[i] < 1)
        {
          x.push_back(P[i]);
          y.push_back(std::log(1 / (1 - D[i])));
        }
    return fit_line(x, y);
  }



  KawakitaFit
  fit_kawakita(const std::vector<double> &P,
               const std::vector<double> &C,
               const double               min_pressure_fraction)
  {
    std::vector<double> x, y;
    const double        smallest = min_pressure_fraction * largest_value(P);
    for (std::size_t i = 0; i < std::min(P.size(), C.size()); ++i)
      if (P[i] > 0 && P[i] >= smallest && C[i] > 0)
        {
          x.push_back(P[i]);
          y.push_back(P[i] / C[i]);
        }
    KawakitaFit fit;
    fit.line = fit_line(x, y);
    // slope 1/a, intercept 1/(a b)
    fit.a = 1 / fit.line.slope;
    fit.b = fit.line.slope / fit.line.intercept;
    return fit;
  }



  std::vector<std::vector<double>>
  read_columns(const std::string              &statistics_csv,
               const std::vector<std::string> &names)
  {
    std::ifstream in(statistics_csv);
    std::string   line;
    if (!in || !std::getline(in, line))
      throw std::runtime_error("cannot read '" + statistics_csv + "'");
    const std::vector<std::string> header = fields(line);
    std::vector<std::size_t>       index;
    for (const std::string &name : names)
      {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end())
          throw std::runtime_error("'" + statistics_csv + "' has no column " +
                                   name);
        index.push_back(it - header.begin());
      }
    const std::size_t needed = *std::max_element(index.begin(), index.end());
    std::vector<std::vector<double>> columns(names.size());
    while (std::getline(in, line))
      {
        const std::vector<std::string> f = fields(line);
        if (f.size() <= needed)
          continue;
        for (std::size_t k = 0; k < index.size(); ++k)
          columns[k].push_back(std::strtod(f[index[k]].c_str(), nullptr));
      }
    return columns;
  }



  LoadingCurve
  read_loading_curve(const std::string &statistics_csv,
                     const double       initial_gap)
  {
    const std::vector<std::vector<double>> c = read_columns(
      statistics_csv,
      {"punch_displacement", "upper_punch_stress", "relative_density"});
    LoadingCurve curve;
    double       farthest = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < c[0].size(); ++i)
      if (c[0][i] > farthest)
        {
          farthest = c[0][i];
          curve.pressure.push_back(c[1][i]);
          curve.density.push_back(c[2][i]);
          curve.volume_reduction.push_back(c[0][i] / initial_gap);
        }
    return curve;
  }



  std::string
  springback_summary(const std::string &statistics_csv)
  {
    const std::vector<std::vector<double>> c =
      read_columns(statistics_csv,
                   {"punch_displacement",
                    "upper_punch_force",
                    "compact_height",
                    "compact_diameter",
                    "envelope_density"});
    const std::vector<double> &stroke = c[0];
    if (stroke.empty())
      return "";
    const std::size_t full =
      std::max_element(stroke.begin(), stroke.end()) - stroke.begin();
    std::size_t last = stroke.size() - 1;
    // a press cycle: the compact as the unloading left it, before the
    // ejection pushes it out of the die (a file without the phase column
    // is taken as it is)
    try
      {
        const std::vector<double> phase =
          read_columns(statistics_csv, {"phase"})[0];
        for (std::size_t i = full; i < phase.size(); ++i)
          if (phase[i] == static_cast<double>(PressPhase::eject))
            {
              last = i - 1;
              break;
            }
      }
    catch (const std::exception &)
      {}
    // unloaded: the punch back from its farthest travel, and off the
    // compact (no force left on it)
    if (!(stroke[last] < stroke[full]) || c[1][last] != 0.)
      return "";
    const auto percent = [](const double after, const double before) {
      return 100 * (after - before) / before;
    };
    std::ostringstream s;
    s << std::setprecision(4) << "Springback after unloading from a stroke of "
      << stroke[full] << " mm: axial " << percent(c[2][last], c[2][full])
      << " % (compact height " << c[2][full] << " -> " << c[2][last]
      << " mm), radial " << percent(c[3][last], c[3][full]) << " % (diameter "
      << c[3][full] << " -> " << c[3][last] << " mm); envelope density "
      << 100 * c[4][full] << " -> " << 100 * c[4][last] << " %\n";
    return s.str();
  }



  std::string
  ejection_summary(const std::string &statistics_csv)
  {
    std::vector<std::vector<double>> c;
    try
      {
        c = read_columns(statistics_csv,
                         {"phase",
                          "lower_punch_force",
                          "lower_punch_displacement",
                          "lower_punch_stress"});
      }
    catch (const std::exception &)
      {
        return "";
      }
    std::size_t peak = c[0].size(), first = peak, last = peak;
    for (std::size_t i = 0; i < c[0].size(); ++i)
      if (c[0][i] == static_cast<double>(PressPhase::eject))
        {
          if (first == c[0].size())
            first = i;
          last = i;
          if (peak == c[0].size() || c[1][i] > c[1][peak])
            peak = i;
        }
    if (peak == c[0].size())
      return "";
    // the travel is the lower punch's rise in the die: a lowered die
    // (withdrawal) counts as a rise (a file without the column: none)
    try
      {
        const std::vector<double> die =
          read_columns(statistics_csv, {"die_displacement"})[0];
        for (std::size_t i = 0; i < c[2].size(); ++i)
          if (std::isfinite(die[i]))
            c[2][i] -= die[i];
      }
    catch (const std::exception &)
      {}
    // the rise where the punch stood still is its history's round-off in
    // time (e.g. 7e-16 mm): printed as 0
    for (double &rise : c[2])
      if (std::abs(rise) < 1e-12)
        rise = 0.;
    std::ostringstream s;
    s << std::setprecision(4) << "Ejection over a lower punch rise of "
      << c[2][first > 0 ? first - 1 : first] << " -> " << c[2][last]
      << " mm: peak force " << c[1][peak] << " N (" << c[3][peak]
      << " MPa over the bore) at a rise of " << c[2][peak] << " mm; "
      << c[1][last] << " N at the end\n";
    // out of the die at the end (the wall carries nothing): the compact's
    // springback against the farthest stroke, now free radially
    try
      {
        const std::vector<std::vector<double>> e =
          read_columns(statistics_csv,
                       {"die_wall_radial_force",
                        "punch_displacement",
                        "compact_height",
                        "compact_diameter",
                        "envelope_density"});
        const std::size_t full =
          std::max_element(e[1].begin(), e[1].end()) - e[1].begin();
        if (e[0][last] == 0. && full < first)
          {
            const auto percent = [](const double after, const double before) {
              return 100 * (after - before) / before;
            };
            s << "Out of the die after the ejection: compact height "
              << e[2][last] << " mm, diameter " << e[3][last]
              << " mm (from the farthest stroke: axial "
              << percent(e[2][last], e[2][full]) << " %, radial "
              << percent(e[3][last], e[3][full]) << " %); envelope density "
              << 100 * e[4][full] << " -> " << 100 * e[4][last] << " %\n";
          }
      }
    catch (const std::exception &)
      {}
    return s.str();
  }



  std::string
  contact_summary(const std::string &statistics_csv)
  {
    std::vector<std::vector<double>> c;
    try
      {
        c = read_columns(statistics_csv,
                         {"punch_displacement",
                          "relative_density",
                          "coordination_number",
                          "contact_area_fraction"});
      }
    catch (const std::exception &)
      {
        return "";
      }
    if (c[0].empty())
      return "";
    const std::size_t full =
      std::max_element(c[0].begin(), c[0].end()) - c[0].begin();
    if (!(c[2][full] > 0.))
      return "";
    std::ostringstream s;
    s << std::setprecision(4) << "Contacts at the farthest stroke ("
      << c[0][full] << " mm";
    if (std::isfinite(c[1][full]))
      s << ", " << 100 * c[1][full] << " % relative density";
    s << "): mean coordination number " << c[2][full]
      << ", contact area fraction " << 100 * c[3][full] << " %\n";
    return s.str();
  }



  std::string
  compaction_summary(const LoadingCurve &curve)
  {
    std::size_t largest = 0;
    for (std::size_t i = 0; i < curve.pressure.size(); ++i)
      if (curve.pressure[i] > curve.pressure[largest])
        largest = i;
    constexpr double upper_half = 0.5;
    const LineFit    heckel =
      fit_heckel(curve.pressure, curve.density, upper_half);
    const KawakitaFit kawakita =
      fit_kawakita(curve.pressure, curve.volume_reduction, upper_half);
    if (heckel.points < 3 || kawakita.line.points < 3)
      return "";
    std::ostringstream s;
    s << std::setprecision(4) << "Compaction: largest upper punch stress "
      << curve.pressure[largest] << " MPa at " << 100 * curve.density[largest]
      << " % relative density\n"
      << "  Heckel ln(1/(1-D)) = K P + A over " << heckel.points
      << " loading steps (P >= half the largest): K = " << heckel.slope
      << " 1/MPa (yield pressure 1/K = " << 1 / heckel.slope
      << " MPa), A = " << heckel.intercept << ", R^2 = " << heckel.r_squared
      << "\n"
      << "  Kawakita P/C = P/a + 1/(a b) over " << kawakita.line.points
      << " loading steps (the same): a = " << kawakita.a
      << ", b = " << kawakita.b << " 1/MPa (1/b = " << 1 / kawakita.b
      << " MPa), R^2 = " << kawakita.line.r_squared << "\n";
    return s.str();
  }
} // namespace densify
