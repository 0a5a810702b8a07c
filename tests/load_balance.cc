// Balanced ranks: a column collapse on two ranks whose grid is repartitioned
// by the points in each cell gives the same time series as the run that
// keeps p4est's even split of the cells, to round-off, for the explicit
// scheme and for Newmark. The column fills the lower rows of its grid, so
// the even split gives one rank 1.9 times the mean number of points; the
// first check, before the first step, must find that, repartition, and
// leave the ranks within 5 % of each other. Every later check repartitions again (tolerance 1), so
// the points move between ranks many times in the explicit run. A block
// sliding on a friction wall with Newmark checks that the nodes that stick
// and slide keep doing so across each repartition.

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "tests.h"

using namespace dealii;

namespace
{
  const std::vector<std::string> coarse_column = {
    "Grid/Arguments=40, 13 : 0, 0 : 8, 2.6 : true"};

  /** `settings` with a check every `interval` steps that repartitions. */
  std::vector<std::string>
  balanced_every(std::vector<std::string> settings,
                 const unsigned int       interval)
  {
    settings.push_back("Load balance/Check interval=" +
                       std::to_string(interval));
    settings.push_back("Load balance/Imbalance tolerance=1");
    return settings;
  }



  void
  compare(const std::string &             title,
          const std::string &             scene,
          const std::vector<std::string> &settings,
          const unsigned int              interval,
          const double                    balanced_within)
  {
    deallog << "--- " << title << std::endl;
    const std::string name = "output-" + title.substr(0, title.find(' '));
    const std::vector<std::string> balanced =
      balanced_every(settings, interval);
    std::vector<std::string> even_split = settings;
    even_split.push_back("Load balance/Check interval=0");
    std::string screen;
    auto even  = mpm_tests::run_scene(scene, name + "-even", even_split);
    auto moved =
      mpm_tests::run_scene(scene, name + "-balanced", balanced, &screen);
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;
    auto record = mpm_tests::read_csv(name + "-balanced/load_balance.csv");
    const auto & repartitioned = record["repartitioned"];
    const unsigned int n_repartitions =
      std::count(repartitioned.begin(), repartitioned.end(), 1.);
    double later = 0.;
    for (unsigned int n = 1; n < record["point_imbalance"].size(); ++n)
      later = std::max(later, record["point_imbalance"][n]);
    deallog << n_repartitions << " repartitions in "
            << repartitioned.size() << " checks" << std::endl;
    mpm_tests::check("at least three repartitions", n_repartitions >= 3);
    mpm_tests::check("a check before the first step and every " +
                       std::to_string(interval) + " steps after it",
                     record["step"][0] == 0. &&
                       record["step"][1] == interval &&
                       record["ranks"][0] == 2.);
    mpm_tests::check("the even split of the cells: one rank holds more than "
                     "1.8 times the mean number of points",
                     record["point_imbalance"][0] > 1.8 &&
                       repartitioned[0] == 1.);
    std::ostringstream within;
    within << balanced_within;
    mpm_tests::check("after the first repartition no rank holds more than " +
                       within.str() + " times the mean",
                     later > 1. && later < balanced_within);
    mpm_tests::check("the run says so on the screen",
                     screen.find("load balance at step 0: weight "
                                 "imbalance 1.") !=
                       std::string::npos);
    const double gap = mpm_tests::largest_difference(even, moved);
    mpm_tests::check("the time series equals the unbalanced run's to 1e-9 "
                     "of each column's largest value",
                     gap < 1e-9);
  }



  /**
   * A balanced Newmark run stopped at `stop` (a step boundary: the steps
   * are fixed) after several repartitions and continued with --restart
   * repeats the run made in one go, to the time series' last digit: the
   * restart must rebuild the partition and the rank-local numbering of
   * cells and nodes that the run had, in which the contact set and the
   * order of the points are saved.
   */
  void
  continued(const std::string &             title,
            const std::string &             scene,
            const std::vector<std::string> &settings,
            const unsigned int              interval,
            const double                    stop,
            const double                    end)
  {
    deallog << "--- " << title << std::endl;
    const std::string name = "output-" + title.substr(0, title.find(' '));
    std::vector<std::string> balanced = balanced_every(settings, interval);
    balanced.push_back("Checkpoint/Wall time interval=1e9");
    std::ostringstream end_time, stop_time;
    end_time << "Time stepping/End time=" << end;
    stop_time << "Time stepping/End time=" << stop;
    std::vector<std::string> straight = balanced, first = balanced;
    straight.push_back(end_time.str());
    first.push_back(stop_time.str());
    auto whole = mpm_tests::run_scene(scene, name + "-whole", straight);
    mpm_tests::run_scene(scene, name + "-parts", first);

    std::vector<std::string> second = balanced;
    second.push_back(end_time.str());
    int  code  = -1;
    auto parts = mpm_tests::run_scene(
      scene, name + "-parts", second, nullptr, &code, true);
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;
    auto record = mpm_tests::read_csv(name + "-parts/load_balance.csv");
    auto record_whole =
      mpm_tests::read_csv(name + "-whole/load_balance.csv");
    unsigned int before_stop = 0;
    for (unsigned int n = 0; n < record["time"].size(); ++n)
      before_stop += record["repartitioned"][n] == 1. &&
                     record["time"][n] < stop - 1e-12;
    deallog << before_stop << " repartitions before the stop" << std::endl;
    mpm_tests::check("the continued part exits with 0, after at least two "
                     "repartitions before the stop",
                     code == 0 && before_stop >= 2);
    mpm_tests::check("load_balance.csv holds each check once, as the run "
                     "made in one go does",
                     record["step"] == record_whole["step"]);
    mpm_tests::check("the time series equals the run made in one go to the "
                     "last digit",
                     mpm_tests::largest_difference(whole, parts) == 0.);
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  std::vector<std::string> explicit_run = coarse_column;
  explicit_run.push_back("Time stepping/End time=0.3");
  compare("explicit column collapse, 0.3 s",
          "../prm/column_collapse.prm",
          explicit_run,
          10,
          1.05);

  std::vector<std::string> newmark = coarse_column;
  for (const std::string &s : {"Time stepping/End time=0.1",
                               "Time stepping/Scheme=Newmark",
                               "Time stepping/Time step=0.005",
                               "Newmark/Mass matrix=lumped",
                               "Newton/Line search=true"})
    newmark.push_back(s);
  compare("Newmark column collapse, 0.1 s",
          "../prm/column_collapse.prm",
          newmark,
          5,
          1.05);

  // The nodes that stick to and slide on a friction wall are a state of
  // the implicit step that lives on the grid's nodes: a repartition numbers
  // them anew and hands them to other ranks. Its 128 points come in cells
  // of 4 that p4est keeps in families of 4 cells, so the balance is
  // coarse.
  compare("friction block sliding on an incline, Newmark, 0.5 s",
          "scenes/friction_block.prm",
          {"Time stepping/Scheme=Newmark",
           "Time stepping/Time step=0.005",
           "Newmark/Bossak alpha=-0.3"},
          10,
          1.3);

  // Stopped at step 7, after the checks at 0, 3 and 6 repartitioned (the
  // later End time entry wins).
  continued("Newmark column collapse continued after 3 repartitions",
            "../prm/column_collapse.prm",
            newmark,
            3,
            0.035,
            0.07);
  continued("friction block continued after 5 repartitions, Newmark",
            "scenes/friction_block.prm",
            {"Time stepping/Scheme=Newmark",
             "Time stepping/Time step=0.005",
             "Newmark/Bossak alpha=-0.3"},
            10,
            0.25,
            0.4);
  return 0;
}
