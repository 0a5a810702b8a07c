#ifndef mpm_core_parse_h
#define mpm_core_parse_h

#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <mpm/core/input_error.h>

#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Parse `dim` comma-separated numbers, e.g. "0.2, 0.8", into a point.
   * `entry` names the parameter for the error message.
   */
  template <int dim>
  Point<dim>
  parse_point(const std::string &text, const std::string &entry)
  {
    const std::vector<std::string> parts =
      Utilities::split_string_list(text, ',');
    if (parts.size() != dim)
      throw InputError(entry + " = '" + text + "' must have " +
                       std::to_string(dim) +
                       " comma-separated coordinates.");
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      {
        try
          {
            std::size_t used = 0;
            p[d]             = std::stod(parts[d], &used);
            if (used != parts[d].size())
              throw std::invalid_argument(parts[d]);
          }
        catch (const std::exception &)
          {
            throw InputError(entry + " = '" + text + "': '" + parts[d] +
                             "' is not a number.");
          }
      }
    return p;
  }

  /** Parse a ';'-separated list of points, e.g. "0,0; 1,0; 1,1". */
  template <int dim>
  std::vector<Point<dim>>
  parse_point_list(const std::string &text, const std::string &entry)
  {
    std::vector<Point<dim>> points;
    for (const std::string &part : Utilities::split_string_list(text, ';'))
      if (!part.empty())
        points.push_back(parse_point<dim>(part, entry));
    return points;
  }
} // namespace mpm

#endif
