// Mixtures by fraction: Particles/Material fractions gives each material
// round(fraction * N) particles (largest remainders first), drawn by a
// seeded shuffle: the same seed gives the same mixture, another seed another
// one; bad fractions are one-line errors.
#include <densify/scene.h>

#include "test_utilities.h"

#include <iostream>
#include <map>

int
main()
{
  using namespace densify;
  auto draw = [](const unsigned int n, const std::string &f, const unsigned s) {
    std::vector<Particle> particles(n);
    draw_materials(f, s, particles);
    std::vector<std::string> names;
    for (const Particle &p : particles)
      names.push_back(p.material);
    return names;
  };
  auto counts = [](const std::vector<std::string> &names) {
    std::map<std::string, unsigned int> c;
    for (const std::string &n : names)
      ++c[n];
    return c;
  };

  const auto a = draw(100, "Sn:0.5, Fe:0.3, Cu:0.2", 1);
  auto       c = counts(a);
  std::cout << "100 particles Sn:0.5, Fe:0.3, Cu:0.2 -> " << c["Sn"] << ' '
            << c["Fe"] << ' ' << c["Cu"] << ": "
            << testing::yes(c["Sn"] == 50 && c["Fe"] == 30 && c["Cu"] == 20)
            << std::endl;
  std::cout << "same seed, same mixture: "
            << testing::yes(a == draw(100, "Sn:0.5, Fe:0.3, Cu:0.2", 1))
            << "; another seed, another: "
            << testing::yes(a != draw(100, "Sn:0.5, Fe:0.3, Cu:0.2", 2))
            << std::endl;
  c = counts(draw(7, "Sn:0.5, Fe:0.5", 3));
  std::cout << "7 particles Sn:0.5, Fe:0.5 -> " << c["Sn"] << ' ' << c["Fe"]
            << ": "
            << testing::yes(c["Sn"] + c["Fe"] == 7 && c["Sn"] >= 3 &&
                            c["Fe"] >= 3)
            << std::endl;
  for (const std::string bad : {"Sn:0.5, Fe:0.6", "Sn:abc", "Sn", "Sn:-0.1"})
    {
      bool thrown = false;
      try
        {
          draw(10, bad, 1);
        }
      catch (const std::runtime_error &e)
        {
          thrown = std::string(e.what()).find("Particles/Material fractions") !=
                   std::string::npos;
        }
      std::cout << "'" << bad
                << "' rejected naming the entry: " << testing::yes(thrown)
                << std::endl;
    }
  return testing::all_passed ? 0 : 1;
}
