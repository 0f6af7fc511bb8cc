// The numbers in parameter text: lists of points and tables of time and
// value, and the interpolation in such a table.
#include <deal.II/base/utilities.h>

#include <densify/parameters.h>

#include <cmath>
#include <stdexcept>

namespace densify
{
  std::vector<Point<3>>
  parse_points(const std::string &text, const std::string &what)
  {
    std::vector<Point<3>> points;
    for (const std::string &item : Utilities::split_string_list(text, ';'))
      {
        if (item.empty())
          continue;
        const std::vector<std::string> xyz =
          Utilities::split_string_list(item, ',');
        if (xyz.size() != 3)
          throw std::runtime_error(what + ": '" + item +
                                   "' is not a point 'x,y,z'");
        Point<3> p;
        for (unsigned int d = 0; d < 3; ++d)
          try
            {
              p[d] = Utilities::string_to_double(xyz[d]);
            }
          catch (...)
            {
              throw std::runtime_error(what + ": '" + xyz[d] +
                                       "' is not a number");
            }
        for (unsigned int d = 0; d < 3; ++d)
          if (!std::isfinite(p[d]))
            throw std::runtime_error(what + ": '" + item +
                                     "' is not a point of finite numbers");
        points.push_back(p);
      }
    return points;
  }



  std::vector<std::pair<double, double>>
  parse_table(const std::string &text, const std::string &what)
  {
    std::vector<std::pair<double, double>> table;
    for (const std::string &item : Utilities::split_string_list(text, ','))
      {
        const std::vector<std::string> tv =
          Utilities::split_string_list(item, ':');
        if (tv.size() != 2)
          throw std::runtime_error(what + ": '" + item +
                                   "' is not a pair 'time:value'");
        try
          {
            table.emplace_back(Utilities::string_to_double(tv[0]),
                               Utilities::string_to_double(tv[1]));
          }
        catch (...)
          {
            throw std::runtime_error(what + ": '" + item +
                                     "' is not a pair of numbers");
          }
        if (!std::isfinite(table.back().first) ||
            !std::isfinite(table.back().second))
          throw std::runtime_error(what + ": '" + item +
                                   "' is not a pair of finite numbers");
      }
    if (table.empty())
      throw std::runtime_error(what + ": empty table");
    for (unsigned int i = 1; i < table.size(); ++i)
      if (!(table[i].first > table[i - 1].first))
        throw std::runtime_error(what + ": times must increase ('" + text +
                                 "')");
    return table;
  }



  double
  interpolate(const std::vector<std::pair<double, double>> &table,
              const double                                  t)
  {
    if (t <= table.front().first)
      return table.front().second;
    for (unsigned int i = 1; i < table.size(); ++i)
      if (t <= table[i].first)
        {
          const double s =
            (t - table[i - 1].first) / (table[i].first - table[i - 1].first);
          return (1. - s) * table[i - 1].second + s * table[i].second;
        }
    return table.back().second;
  }
} // namespace densify
