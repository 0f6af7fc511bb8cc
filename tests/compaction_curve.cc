// The field's numbers of a die compaction (compaction_curve.h):
// - Heckel's and Kawakita's constants recovered from synthetic curves that
//   follow the equations exactly, to 1e-6 (relative), the fits ignoring a
//   rearrangement stage below 0.1 of the largest pressure that does not
//   follow them;
// - punch stresses and the die wall's pressure of known forces in closed
//   form, NaN without die or punches;
// - the loading curve read from a statistics.csv by column name: rows that
//   do not advance the punch (a hold, an unloading) left out, the volume
//   reduction stroke / initial gap.
#include <densify/postprocess/compaction_curve.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

using namespace densify;

namespace
{
  unsigned int failures = 0;

  void
  check(const std::string &what, const double value, const double expected)
  {
    const double error = std::abs(value - expected) / std::abs(expected);
    const bool   ok    = error <= 1e-6;
    std::printf("%-40s %s\n", what.c_str(), ok ? "ok" : "FAILED");
    if (!ok)
      {
        std::cerr << what << ": " << value << " against " << expected
                  << " (relative error " << error << ")" << std::endl;
        ++failures;
      }
  }
} // namespace



int
main()
{
  // Heckel: ln(1/(1 - D)) = K P + A from 20 to 200 MPa, below 20 MPa a
  // rearrangement stage with lower densities
  {
    const double        K = 0.0123, A = 0.87;
    std::vector<double> P, D;
    for (unsigned int i = 1; i <= 200; ++i)
      {
        P.push_back(i);
        const double d = 1 - std::exp(-(K * i + A));
        D.push_back(i < 20 ? 0.8 * d : d);
      }
    const LineFit fit = fit_heckel(P, D);
    check("Heckel K", fit.slope, K);
    check("Heckel A", fit.intercept, A);
    check("Heckel R^2", fit.r_squared, 1.);
    std::printf("Heckel points used: %u\n", fit.points);
  }

  // Kawakita: C = a b P / (1 + b P) from 30 to 300 MPa, below 30 MPa a
  // rearrangement stage with larger volume reductions
  {
    const double        a = 0.42, b = 0.067;
    std::vector<double> P, C;
    for (unsigned int i = 1; i <= 600; ++i)
      {
        const double p = 0.5 * i;
        P.push_back(p);
        const double c = a * b * p / (1 + b * p);
        C.push_back(p < 30 ? 1.5 * c : c);
      }
    const KawakitaFit fit = fit_kawakita(P, C);
    check("Kawakita a", fit.a, a);
    check("Kawakita b", fit.b, b);
  }

  // a die of 20 mm, 1000 N on the upper punch, 800 N on the lower, 500 N
  // radially on the wall over a gap of 5 mm
  {
    const double      pi = 3.14159265358979323846;
    const DieStresses s  = die_stresses(1000, 800, 500, 20, 5);
    check("upper punch stress", s.upper_punch, 1000 / (pi * 100));
    check("lower punch stress", s.lower_punch, 800 / (pi * 100));
    check("die wall pressure", s.die_wall, 500 / (pi * 20 * 5));
    check("radial/axial ratio", s.radial_axial_ratio, 0.5);
    const DieStresses none = die_stresses(1000, 800, 500, 0, 5);
    std::printf("without die: %s\n",
                std::isnan(none.upper_punch) && std::isnan(none.die_wall) &&
                    std::isnan(none.radial_axial_ratio) ?
                  "NaN" :
                  "FAILED");
    const DieStresses no_gap = die_stresses(1000, 800, 500, 20, 0);
    std::printf("without a pair of punches: die wall %s\n",
                std::isnan(no_gap.die_wall) ? "NaN" : "FAILED");
  }

  // the loading curve of a statistics.csv: columns by name, a hold and an
  // unloading left out
  {
    {
      std::ofstream csv("statistics.csv");
      csv << "relative_density,step,punch_displacement,upper_punch_stress\n"
          << "0.5,1,0.1,10\n"
          << "0.6,2,0.2,20\n"
          << "0.6,3,0.2,19\n"
          << "0.55,4,0.15,5\n"
          << "0.7,5,0.3,40\n";
    }
    const LoadingCurve curve = read_loading_curve("statistics.csv", 2.);
    std::printf("loading rows: %zu\n", curve.pressure.size());
    for (std::size_t i = 0; i < curve.pressure.size(); ++i)
      std::printf("  P %g MPa, D %g, C %g\n",
                  curve.pressure[i],
                  curve.density[i],
                  curve.volume_reduction[i]);
  }

  std::printf("%s\n", failures == 0 ? "all checks passed" : "FAILURES");
  return failures == 0 ? 0 : 1;
}
