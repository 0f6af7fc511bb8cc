// The quasi-static guard of explicit runs (quasi_static_guard.h) on
// synthetic stations:
// - a loose bed's stations, whose upper punch force stays below the load
//   floor, are not judged, whatever their kinetic energy (KE/IE 200 %) and
//   force balance (a third of the force not carried);
// - the first station that reaches the floor arms the guard: from it on
//   the kinetic energy gained since that station above the limit's fraction
//   of the internal work done since is a breach (the energy the loose bed
//   had is not counted), and so is a lasting imbalance of the force means
//   over the last ten stations (those before the floor included), which a
//   single station's swing does not make;
// - once armed the guard stays armed; the force balance is not judged at
//   stations below the floor (an unloading), the kinetic energy is.
#include <densify/postprocess/quasi_static_guard.h>

#include <iostream>
#include <string>

using namespace densify;

namespace
{
  StepStatistics
  station(const double upper,
          const double carried,
          const double kinetic,
          const double internal)
  {
    static unsigned int step = 0;
    StepStatistics      s;
    s.step              = ++step;
    s.upper_punch_force = upper;
    s.lower_punch_force = carried;
    s.kinetic_energy    = kinetic;
    s.internal_work     = internal;
    return s;
  }

  void
  report(const std::string &what, const std::string &breach)
  {
    std::cout << what << ": " << (breach.empty() ? "within the limits" : breach)
              << std::endl;
  }
} // namespace



int
main()
{
  QuasiStaticLimits limits;
  limits.kinetic_ratio   = 0.25;
  limits.force_imbalance = 0.5;
  limits.load_floor      = 100.;

  QuasiStaticGuard guard(limits);
  std::cout << "active " << guard.active() << ", judging " << guard.judging()
            << std::endl;
  for (unsigned int i = 0; i < 5; ++i)
    report("loose bed, 60 N, 40 N carried, KE/IE 200 %",
           guard.add(station(60., 40., 2., 1.)));
  std::cout << "judging " << guard.judging() << std::endl;
  report("first station at the floor, 90 N carried, KE/IE 200 %",
         guard.add(station(100., 90., 2., 1.)));
  std::cout << "judging " << guard.judging() << std::endl;
  report("gained 0.2 mJ of kinetic energy over 1 mJ of work",
         guard.add(station(200., 190., 2.2, 2.)));
  report("gained 0.6 mJ over 2 mJ", guard.add(station(300., 290., 2.6, 3.)));
  for (unsigned int i = 0; i < 10; ++i)
    guard.add(station(1000., 1000., 2., 100.));
  report("one station 70 % apart after ten balanced ones",
         guard.add(station(1000., 300., 2., 100.)));
  std::string breach;
  for (unsigned int i = 0; i < 10 && breach.empty(); ++i)
    breach = guard.add(station(1000., 300., 2., 100.));
  report("ten stations 70 % apart", breach);

  QuasiStaticGuard unloading(limits);
  for (unsigned int i = 0; i < 10; ++i)
    unloading.add(station(1000., 1000., 0.01, 100.));
  std::string unloaded;
  for (unsigned int i = 0; i < 10; ++i)
    unloaded += unloading.add(station(1., 0., 0.01, 90.));
  std::cout << "unloaded to 1 N, nothing carried: judging "
            << unloading.judging() << std::endl;
  report("ten stations unloaded below the floor", unloaded);
  report("unloaded, gained 20 mJ over 10 mJ of work",
         unloading.add(station(1., 0., 20., 110.)));
}
