#ifndef mpm_base_parse_h
#define mpm_base_parse_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <mpm/base/input_error.h>

#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The number `text` is, all of it; an InputError `message` otherwise.
   */
  inline double
  parse_number(const std::string &text, const std::string &message)
  {
    try
      {
        std::size_t  used  = 0;
        const double value = std::stod(text, &used);
        if (used == text.size())
          return value;
      }
    catch (const std::exception &)
      {}
    throw InputError(message);
  }

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
      p[d] = parse_number(parts[d],
                          entry + " = '" + text + "': '" + parts[d] +
                            "' is not a number.");
    return p;
  }

  /**
   * A list item that may end in 'until t' ("orifice until 1.5"): the item
   * before it, and t, or infinity without it. `entry` names the parameter
   * for the message.
   */
  inline std::pair<std::string, double>
  split_until(const std::string &item, const std::string &entry)
  {
    const std::string::size_type at = item.find(" until ");
    if (at == std::string::npos)
      return {item, std::numeric_limits<double>::infinity()};
    const std::string time = Utilities::trim(item.substr(at + 7));
    return {Utilities::trim(item.substr(0, at)),
            parse_number(time,
                         entry + ": '" + item +
                           "': the time after 'until' is not a number.")};
  }

  /**
   * A friction coefficient: a number, 0 or more, or inf (no sliding).
   * `what` names it for the message.
   */
  inline double
  parse_friction_coefficient(const std::string &text, const std::string &what)
  {
    const double friction =
      parse_number(text, what + " = '" + text + "' is not a number.");
    if (!(friction >= 0.))
      throw InputError(what + " = " + text +
                       " must be 0 or more (inf: no sliding).");
    return friction;
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

  /**
   * A function of `variables` (e.g. "x,y,t") with one expression per
   * component, evaluated once at `probe` so that a bad expression fails
   * here, with `entry` named in the message, rather than mid-run.
   */
  template <int dim>
  std::unique_ptr<FunctionParser<dim>>
  parse_function(const std::vector<std::string> &expressions,
                 const std::string &             variables,
                 const Point<dim> &              probe,
                 const std::string &             entry)
  {
    auto function =
      std::make_unique<FunctionParser<dim>>(expressions.size());
    // muparser writes its own report of a bad expression to std::cerr; the
    // message below says the same once, naming the entry.
    std::ostringstream    parser_report;
    std::streambuf *const cerr_buffer = std::cerr.rdbuf(parser_report.rdbuf());
    try
      {
        function->initialize(variables, expressions, {{"pi", numbers::PI}});
        function->value(probe, 0);
        std::cerr.rdbuf(cerr_buffer);
      }
    catch (const ExceptionBase &e)
      {
        std::cerr.rdbuf(cerr_buffer);
        std::ostringstream info;
        e.print_info(info);
        std::string text;
        for (const auto &expression : expressions)
          text += (text.empty() ? "" : "; ") + expression;
        throw InputError(entry + " = '" + text +
                         "' is not a valid expression: " + info.str());
      }
    return function;
  }
} // namespace mpm

#endif
