// Shared helpers for the .cc tests: deallog goes to the file `output`
// (rank 0 only), which numdiff compares with the test's .output file.
#ifndef mpm_tests_h
#define mpm_tests_h

#include <deal.II/base/logstream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/core/application.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <iostream>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mpm_tests
{
  inline std::ofstream logfile;

  /**
   * A map smooth and one-to-one on [0,1]^dim that leaves the boundary in
   * place: a grid of boxes becomes general quadrilaterals (hexahedra).
   */
  template <int dim>
  dealii::Point<dim>
  distort(const dealii::Point<dim> &p)
  {
    dealii::Point<dim> q = p;
    for (unsigned int d = 0; d < dim; ++d)
      q[d] += 0.06 * std::sin(dealii::numbers::PI * p[(d + 1) % dim]) *
              std::sin(2 * dealii::numbers::PI * p[d]);
    return q;
  }

  /** The von Mises equivalent stress q = sqrt(3/2 s : s). */
  inline double
  von_mises_q(const dealii::SymmetricTensor<2, 3> &stress)
  {
    const dealii::SymmetricTensor<2, 3> s = dealii::deviator(stress);
    return std::sqrt(1.5 * (s * s));
  }

  inline void
  initlog()
  {
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        logfile.open("output");
        dealii::deallog.attach(logfile, false);
      }
    dealii::deallog.depth_console(0);
    dealii::deallog << std::setprecision(6);
  }

  /** Print a check in a form whose text does not depend on round-off. */
  inline void
  check(const std::string &what, const bool passed)
  {
    dealii::deallog << (passed ? "PASS " : "FAIL ") << what << std::endl;
  }

  /** Path of a file next to the tests' sources. */
  inline std::string
  source_file(const std::string &name)
  {
    return std::string(SOURCE_DIR) + "/" + name;
  }
  /**
   * The columns of a time series by name. A run that failed may have
   * written no rows, or no file: then every column holds two NaN, so that
   * a test reading its first, second or last row prints FAIL instead of
   * reading past the end.
   */
  class Columns : public std::map<std::string, std::vector<double>>
  {
  public:
    std::vector<double> &
    operator[](const std::string &name)
    {
      std::vector<double> &column =
        std::map<std::string, std::vector<double>>::operator[](name);
      if (column.empty())
        column.assign(2, std::numeric_limits<double>::quiet_NaN());
      return column;
    }
  };

  /** The columns of a CSV file with a header line, by name. */
  inline Columns
  read_csv(const std::string &filename)
  {
    std::ifstream            in(filename);
    std::string              line;
    std::vector<std::string> names;
    Columns                  columns;
    std::getline(in, line);
    {
      std::istringstream header(line);
      std::string        name;
      while (std::getline(header, name, ','))
        names.push_back(name);
    }
    unsigned int n_rows = 0;
    for (; std::getline(in, line); ++n_rows)
      {
        std::istringstream row(line);
        std::string        value;
        for (unsigned int i = 0; std::getline(row, value, ','); ++i)
          columns.std::map<std::string, std::vector<double>>::operator[](
            names.at(i)).push_back(std::stod(value));
      }
    if (n_rows == 0)
      check(filename + " has rows", false);
    return columns;
  }

  /**
   * The rolling disk of prm/rolling_disk.prm: the centre's displacement
   * along the plane over the exact rolling a t^2 / 2, a = 2/3 g sin 60
   * degrees (benchmarks.md section 2), and the largest change of the
   * centre's height.
   */
  inline std::pair<double, double>
  rolling_disk_ratio_and_drift(Columns &csv)
  {
    const double t       = csv["time"].back();
    const double rolling = 0.5 * (2. / 3.) * 9.81 *
                           std::sin(dealii::numbers::PI / 3.) * t * t;
    double drift = 0.;
    for (const double y : csv["centre_of_mass_y"])
      drift = std::max(drift, std::abs(y - csv["centre_of_mass_y"][0]));
    return {(csv["centre_of_mass_x"].back() - csv["centre_of_mass_x"][0]) /
              rolling,
            drift};
  }

  /**
   * Run a scene through the mpm command line with its output in
   * `directory` (no ParaView files) and the given 'Section/entry=value'
   * settings; log the exit code (and give it in `exit_code`) and return
   * the time series. With `screen`, what the run prints (on rank 0) goes
   * there instead. With `restart`, the run continues from the checkpoint
   * in `directory`.
   */
  inline Columns
  run_scene(const std::string &             scene,
            const std::string &             directory,
            const std::vector<std::string> &settings  = {},
            std::string *                   screen    = nullptr,
            int *                           exit_code = nullptr,
            const bool                      restart   = false)
  {
    std::vector<std::string> arguments = {"--set",
                                          "Output/Directory=" + directory,
                                          "--set",
                                          "Output/Write ParaView output=false"};
    if (restart)
      arguments.insert(arguments.begin(), "--restart");
    for (const auto &s : settings)
      {
        arguments.push_back("--set");
        arguments.push_back(s);
      }
    arguments.push_back(source_file(scene));
    std::ostringstream captured;
    int                code;
    {
      // Puts std::cout back however the run ends.
      struct Redirect
      {
        std::streambuf *original;
        ~Redirect()
        {
          std::cout.rdbuf(original);
        }
      } redirect{screen ? std::cout.rdbuf(captured.rdbuf()) :
                          std::cout.rdbuf()};
      code = mpm::run_command_line(arguments);
    }
    if (screen)
      *screen = captured.str();
    dealii::deallog << directory << ": exit code " << code << std::endl;
    if (exit_code)
      *exit_code = code;
    MPI_Barrier(MPI_COMM_WORLD);
    return read_csv(directory + "/time_series.csv");
  }

  /**
   * The largest difference between two time series over all columns and
   * rows, relative to the largest magnitude of its column; infinity when
   * the rows or columns differ.
   */
  inline double
  largest_difference(Columns &a, Columns &b)
  {
    double largest = 0.;
    for (auto &[name, column] : a)
      {
        const std::vector<double> &other = b[name];
        if (column.size() != other.size() || column.size() < 3)
          return std::numeric_limits<double>::infinity();
        double scale = 0., gap = 0.;
        for (unsigned int n = 0; n < column.size(); ++n)
          {
            scale = std::max(scale, std::abs(column[n]));
            gap   = std::max(gap, std::abs(column[n] - other[n]));
          }
        // NaN compares false: a NaN makes the gap infinite.
        if (!(gap <= scale * 1e300))
          return std::numeric_limits<double>::infinity();
        if (scale > 0.)
          largest = std::max(largest, gap / scale);
      }
    return largest;
  }



  /**
   * The tangent of a non-associated Mohr-Coulomb column (prm/
   * column_collapse.prm on 0.2 m cells, Newmark, 0.2 s: plastic from the
   * third step) against central differences of the residual, through
   * Newton/Check tangent. Its tangent is not symmetric, so a transposed
   * or misplaced entry shows: transposed, it is off by 1e-2 to 4e-2 in 80
   * to 90 % of the checks. The differences match to round-off (5e-8)
   * except where a point lies within the perturbation of a kink of the
   * yield surface: none here, but 4 of MPM's 125 checks to 0.4 s at a
   * perturbation three times as large. So 90 % must be below 1e-6.
   */
  /**
   * The `Newton/Check tangent` lines of a run's screen output: how many
   * there are, and how many measured a gap below `tolerance` (a check not
   * made counts as failed).
   */
  inline std::pair<unsigned int, unsigned int>
  tangent_checks(const std::string &screen, const double tolerance)
  {
    std::istringstream lines(screen);
    unsigned int       checks = 0, matching = 0;
    for (std::string line; std::getline(lines, line);)
      if (line.find("tangent check:") != std::string::npos)
        {
          ++checks;
          matching += line.find("|K d| = ") != std::string::npos &&
                      std::stod(line.substr(line.rfind(' ') + 1)) < tolerance;
        }
    return {checks, matching};
  }

  inline void
  check_plastic_tangent(const std::string &method)
  {
    std::string screen;
    run_scene("../prm/column_collapse.prm",
              "output-tangent-" + method,
              {"Method=" + method,
               "Grid/Arguments=40, 13 : 0, 0 : 8, 2.6 : true",
               "Time stepping/Scheme=Newmark",
               "Time stepping/Time step=0.02",
               "Newmark/Mass matrix=lumped",
               "Time stepping/End time=0.2",
               "Newton/Check tangent=true"},
              &screen);
    const auto [checks, matching] = tangent_checks(screen, 1e-6);
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      check(method + ": plastic column, 0.2 s: the assembled tangent is "
                     "the derivative of the residual (central differences, "
                     "below 1e-6 in 90 % of " +
              std::string(checks >= 40 ? "at least" : "fewer than") +
              " 40 Newton iterations)",
            checks >= 40 && matching >= 0.9 * checks);
  }
  /**
   * A block on a floor y = const under gravity g tilted by theta towards
   * +x (scenes/friction_block.prm): the largest gap, over rows, between the
   * change of momentum since the start and the impulse sum dt (M g - F),
   * F the force on the floor `bottom`,
   * relative to M g t. Summed from the start, so that the 12 digits of
   * the time series' momentum do not limit it.
   */
  inline double
  floor_momentum_balance(Columns &csv, const double g, const double theta)
  {
    const double M   = csv["mass"][0];
    double       gap = 0., impulse_x = 0., impulse_y = 0.;
    for (unsigned int n = 1; n < csv["time"].size(); ++n)
      {
        const double dt = csv["dt"][n];
        // The floor's outward normal is -y, its tangent (the normal turned
        // by +90 degrees) is +x: the material's force on it is
        // (T, -N), the floor's on the material (-T, N).
        impulse_x +=
          dt * (M * g * std::sin(theta) - csv["bottom_tangential_force"][n]);
        impulse_y +=
          dt * (-M * g * std::cos(theta) + csv["bottom_normal_force"][n]);
        gap = std::max(
          gap,
          std::max(std::abs(csv["momentum_x"][n] - csv["momentum_x"][0] -
                            impulse_x),
                   std::abs(csv["momentum_y"][n] - csv["momentum_y"][0] -
                            impulse_y)) /
            (M * g * csv["time"][n]));
      }
    return gap;
  }
} // namespace mpm_tests

#endif
