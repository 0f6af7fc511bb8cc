// The numbers powder engineers read off a die compaction: punch stresses and
// the die wall's pressure in MPa, and the Heckel and Kawakita constants of
// the pressure-density curve.
#pragma once

#include <string>
#include <vector>

namespace densify
{
  /**
   * Mean stresses of a die compaction (MPa, compression positive); NaN where
   * the scene lacks the tool that defines them.
   */
  struct DieStresses
  {
    /// Upper punch force over the die's bore area.
    double upper_punch = 0.;
    /// Lower punch force over the die's bore area.
    double lower_punch = 0.;
    /// The die wall's radial force over the wall area between the punches
    /// (pi x die diameter x punch gap).
    double die_wall = 0.;
    /// die_wall / upper_punch: the ratio of radial to axial stress (the
    /// "transmission" or Janssen coefficient of the compact); 0 while the
    /// upper punch carries no stress.
    double radial_axial_ratio = 0.;
  };

  /**
   * The stresses of @p upper_force, @p lower_force and @p die_radial_force
   * (N) for a die of diameter @p die_diameter (mm; <= 0: no die, all NaN)
   * and punches @p punch_gap (mm; <= 0: no pair of punches, die_wall NaN)
   * apart.
   */
  DieStresses
  die_stresses(const double upper_force,
               const double lower_force,
               const double die_radial_force,
               const double die_diameter,
               const double punch_gap);

  /// A straight line y = slope x + intercept fitted by least squares.
  struct LineFit
  {
    double slope     = 0.;
    double intercept = 0.;
    /// Coefficient of determination (1: the points lie on the line).
    double r_squared = 0.;
    /// Points the fit used (0: no fit; then the numbers are NaN).
    unsigned int points = 0;
  };

  /// The least-squares line through (@p x, @p y); NaN with fewer than 2
  /// points or all x equal.
  LineFit
  fit_line(const std::vector<double> &x, const std::vector<double> &y);

  /**
   * Heckel's equation ln(1/(1 - D)) = K P + A fitted to pressures @p P (MPa)
   * and relative densities @p D (fractions) by least squares, using the
   * points with P at least @p min_pressure_fraction of the largest P and
   * 0 < D < 1. K (1/MPa) is the fit's slope, A its intercept; 1/K is the
   * "yield pressure" of the powder.
   */
  LineFit
  fit_heckel(const std::vector<double> &P,
             const std::vector<double> &D,
             const double               min_pressure_fraction = 0.1);

  /// Kawakita's constants a (-) and b (1/MPa).
  struct KawakitaFit
  {
    double a = 0.;
    double b = 0.;
    /// The line P/C = P/a + 1/(a b) it came from.
    LineFit line;
  };

  /**
   * Kawakita's equation C = a b P / (1 + b P), with the volume reduction
   * C = (V0 - V)/V0 of the compact, fitted in its linear form P/C = P/a +
   * 1/(a b) by least squares to the points with P at least
   * @p min_pressure_fraction of the largest P and C > 0.
   */
  KawakitaFit
  fit_kawakita(const std::vector<double> &P,
               const std::vector<double> &C,
               const double               min_pressure_fraction = 0.1);

  /**
   * The columns @p names of @p statistics_csv (by name, in that order), one
   * entry per complete row. Throws std::runtime_error if the file cannot be
   * read or lacks a column.
   */
  std::vector<std::vector<double>>
  read_columns(const std::string              &statistics_csv,
               const std::vector<std::string> &names);

  /**
   * The loading curve of a run from its statistics.csv (columns by name):
   * the rows where the upper punch reaches a stroke beyond every earlier
   * row, as upper punch stress (MPa), relative density and the volume
   * reduction 1 - gap/gap0 of the compact (@p initial_gap: the punch gap at
   * the start, mm). Throws std::runtime_error if the file cannot be read.
   */
  struct LoadingCurve
  {
    std::vector<double> pressure, density, volume_reduction;
  };
  LoadingCurve
  read_loading_curve(const std::string &statistics_csv,
                     const double       initial_gap);

  /**
   * Lines for the end of a run: the largest punch stress and its density,
   * the Heckel and the Kawakita fit of @p curve over the upper half of its
   * pressure range, where both equations are meant to hold (below it a bed
   * of spheres deforms at point contacts and rearranges); "" with fewer
   * than three points there.
   */
  std::string
  compaction_summary(const LoadingCurve &curve);

  /**
   * A line for the end of a run whose upper punch went back from its
   * farthest stroke and carries no force at the last step: the axial and
   * radial springback (%) of the compact's envelope (compact_height,
   * compact_diameter) from the farthest stroke to the last step, and the
   * envelope density at both; "" otherwise.
   */
  std::string
  springback_summary(const std::string &statistics_csv);

  /**
   * The ejection of a press cycle from @p statistics_csv: the largest force
   * on the lower punch over the rows in the phase eject, the lower punch's
   * rise in the die at it (lower_punch_displacement - die_displacement),
   * and the force when the last row ends (the travel curve is
   * lower_punch_force against that rise over those rows). If the die wall
   * carries nothing at the last row (the compact is out of the die), a
   * second line: the compact's height, diameter and envelope density there
   * against the farthest stroke's (its springback out of the die). "" if
   * no row ejects.
   */
  std::string
  ejection_summary(const std::string &statistics_csv);

  /**
   * The packing at the farthest stroke of @p statistics_csv (the first row
   * that reaches it): the relative density, the mean coordination number
   * and the contact area fraction (%). "" if no two particles touch there
   * or the file has no such columns.
   */
  std::string
  contact_summary(const std::string &statistics_csv);
} // namespace densify
