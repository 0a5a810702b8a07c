// A run stopped after a checkpoint and continued with --restart repeats the
// uninterrupted run to the last bit: its time series and every ParaView file
// (apart from the line with the date) are byte-identical to those of a run
// that never stopped. Each scene runs straight, and again in parts: parts
// with Checkpoint/Stop after near 0 end after exactly one step, and a part
// may raise End time (not in the quasi-static scheme, whose load ramps over
// it), and one continues from checkpoint.old/, as after a run killed
// between the renames that swap a new checkpoint in. The scenes cover the
// explicit scheme (one with two contact groups), the quasi-static scheme,
// Newmark with walls, a wall that ends and an outflow boundary, an inflow
// whose releases fall before, between and after the parts, and the
// meshfree methods with their node cloud. Two cases continue
// runs with other step sizes, as after a run that went unstable, and one
// with another velocity projection. A checkpoint rewritten without one entry
// (as one written before mpm declared it) continues if the entry is at its
// default and is refused if the scene sets it. Bad input for checkpoints is
// in bad_input.cc.

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests.h"

using namespace dealii;

namespace
{
  const std::vector<std::string> stop_after_one_step = {
    "Checkpoint/Wall time interval=1e-9",
    "Checkpoint/Stop after=1e-9"};
  const std::vector<std::string> to_the_end = {
    "Checkpoint/Wall time interval=1e-9"};

  int
  run(const std::string &             scene,
      const std::string &             directory,
      const std::vector<std::string> &settings,
      const bool                      restart)
  {
    std::vector<std::string> arguments = {"--set",
                                          "Output/Directory=" + directory};
    if (restart)
      arguments.push_back("--restart");
    for (const auto &s : settings)
      {
        arguments.push_back("--set");
        arguments.push_back(s);
      }
    arguments.push_back(scene);
    const int code = mpm::run_command_line(arguments);
    MPI_Barrier(MPI_COMM_WORLD);
    return code;
  }

  /** A file's text without deal.II's line with the date of writing. */
  std::string
  contents(const std::filesystem::path &file)
  {
    std::ifstream      in(file);
    std::ostringstream text;
    for (std::string line; std::getline(in, line);)
      if (line.rfind("#This file was generated", 0) != 0)
        text << line << '\n';
    return text.str();
  }

  /**
   * Number of output files of `straight` that `parts` has with the same
   * text, and whether the two directories hold the same output files.
   */
  std::pair<unsigned int, bool>
  identical_files(const std::string &straight, const std::string &parts)
  {
    unsigned int n_identical = 0, n_files = 0;
    for (const auto &entry : std::filesystem::directory_iterator(straight))
      {
        const auto other = std::filesystem::path(parts) / entry.path().filename();
        ++n_files;
        if (std::filesystem::exists(other) &&
            contents(entry.path()) == contents(other))
          ++n_identical;
      }
    unsigned int n_other = 0;
    for (const auto &entry : std::filesystem::directory_iterator(parts))
      if (entry.path().filename().string().rfind("checkpoint", 0) != 0)
        ++n_other;
    return {n_identical, n_identical == n_files && n_other == n_files};
  }

  /**
   * Run `scene` with `settings` straight, then in the given parts: the
   * first starts afresh, the others continue with --restart, each with its
   * own settings added.
   */
  void
  compare(const std::string &                           title,
          const std::string &                           scene,
          const std::vector<std::string> &              settings,
          const std::vector<std::vector<std::string>> &parts,
          const bool kill_between_renames_after_part_2 = false)
  {
    const std::string name =
      "output-" + title.substr(0, title.find(',')) + "-";
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        std::filesystem::remove_all(name + "straight");
        std::filesystem::remove_all(name + "parts");
      }
    MPI_Barrier(MPI_COMM_WORLD);
    deallog << "--- " << title << std::endl;
    mpm_tests::check("straight run exits with 0",
                     run(scene, name + "straight", settings, false) == 0);

    double previous_step = 0.;
    for (unsigned int k = 0; k < parts.size(); ++k)
      {
        std::vector<std::string> part_settings = settings;
        part_settings.insert(part_settings.end(),
                             parts[k].begin(),
                             parts[k].end());
        const int code = run(scene, name + "parts", part_settings, k > 0);
        const double step =
          mpm_tests::read_csv(name + "parts/time_series.csv")["step"].back();
        if (parts[k] == stop_after_one_step)
          mpm_tests::check("part " + std::to_string(k + 1) +
                             " stops after one more step, exit 0",
                           code == 0 && step == previous_step + 1.);
        else
          mpm_tests::check("part " + std::to_string(k + 1) + " exits with 0",
                           code == 0);
        previous_step = step;
        // A run killed between the two renames that swap a checkpoint in
        // leaves only checkpoint.old/.
        if (kill_between_renames_after_part_2 && k == 1 &&
            Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
          std::filesystem::rename(name + "parts/checkpoint",
                                  name + "parts/checkpoint.old");
        MPI_Barrier(MPI_COMM_WORLD);
      }

    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        const auto [n_identical, same_set] =
          identical_files(name + "straight", name + "parts");
        // Identical and written: two missing files would be equal too.
        const std::string series = contents(name + "straight/time_series.csv");
        mpm_tests::check("time series identical",
                         std::count(series.begin(), series.end(), '\n') > 2 &&
                           series ==
                             contents(name + "parts/time_series.csv"));
        mpm_tests::check("every output file identical",
                         same_set && n_identical > 2);
      }
  }

  /**
   * Run `scene` with `settings` in a fresh `directory` until it stops
   * after its first step, with a checkpoint; returns the exit code.
   */
  int
  run_first_step(const std::string &             scene,
                 const std::string &             directory,
                 const std::vector<std::string> &settings)
  {
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::filesystem::remove_all(directory);
    MPI_Barrier(MPI_COMM_WORLD);
    std::vector<std::string> first = settings;
    first.insert(first.end(),
                 stop_after_one_step.begin(),
                 stop_after_one_step.end());
    return run(scene, directory, first, false);
  }

  /**
   * A run stopped after one step and continued with another step entry (as
   * after a run that went unstable): the steps after the restart have the
   * sizes `expected_steps` lists (the first is the step before the stop),
   * and the run reaches End time.
   */
  void
  changed_steps(const std::string &             title,
                const std::string &             scene,
                const std::vector<std::string> &settings,
                const std::string &             changed_entry,
                const std::vector<double> &     expected_steps)
  {
    const std::string        directory = "output-changed-steps";
    std::vector<std::string> second    = settings;
    second.push_back(changed_entry);
    deallog << "--- " << title << std::endl;
    const int first_code  = run_first_step(scene, directory, settings);
    const int second_code = run(scene, directory, second, true);
    auto      csv = mpm_tests::read_csv(directory + "/time_series.csv");
    // The first row is the state at t = 0.
    bool sizes = csv["dt"].size() == expected_steps.size() + 1;
    for (unsigned int n = 0; sizes && n < expected_steps.size(); ++n)
      sizes = std::abs(csv["dt"][n + 1] - expected_steps[n]) <
              1e-12 * expected_steps[n];
    mpm_tests::check("both parts exit with 0",
                     first_code == 0 && second_code == 0);
    mpm_tests::check("the steps have the expected sizes", sizes);
  }

  /**
   * A checkpoint of a scene whose saved entries lack `entry`, as one
   * written before mpm declared it: this rank's file is rewritten without
   * it, and with the names of empty entries as older checkpoints kept them
   * (the file's layout: format version, ranks, the scene's entries, the
   * state and its checksum, which covers the state only). Returns the exit
   * code of the continued run.
   */
  int
  continue_without_entry(const std::string &             scene,
                         const std::vector<std::string> &settings,
                         const std::string &             entry)
  {
    const std::string directory = "output-older-checkpoint";
    if (run_first_step(scene, directory, settings) != 0)
      return -1;
    const std::string file =
      directory + "/checkpoint/rank-" +
      std::to_string(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)) +
      ".bin";
    unsigned int                       version = 0, n_ranks = 0;
    std::map<std::string, std::string> entries;
    std::string                        state;
    std::uint32_t                      checksum = 0;
    {
      std::ifstream                   in(file, std::ios::binary);
      boost::archive::binary_iarchive archive(in);
      archive >> version >> n_ranks >> entries >> state >> checksum;
    }
    const bool had_entry = entries.erase(entry) == 1;
    // Written before mpm parsed the PRM form, a checkpoint kept an entry
    // with an empty value as its padded name followed by '='.
    std::map<std::string, std::string> older;
    for (const auto &[name, value] : entries)
      older[value.empty() ? name + "     =" : name] = value;
    entries = older;
    {
      std::ofstream                   out(file, std::ios::binary);
      boost::archive::binary_oarchive archive(out);
      archive << version << n_ranks << entries << state << checksum;
    }
    MPI_Barrier(MPI_COMM_WORLD);
    const int code = had_entry ? run(scene, directory, settings, true) : -1;
    deallog << "without " << entry << ": exit code " << code << std::endl;
    return code;
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  const std::string prm = mpm_tests::source_file("../prm/");

  compare("two_disks, explicit, killed between renames after part 2",
          prm + "two_disks.prm",
          {"Time stepping/End time=0.3", "Output/Interval=0.05"},
          {stop_after_one_step,
           stop_after_one_step,
           stop_after_one_step,
           to_the_end},
          true);

  // Two contact groups: their fields, normals and surfaces are made anew
  // at every step, so nothing of them goes into the checkpoint.
  compare("block_on_slope, contact between bodies",
          prm + "block_on_slope.prm",
          {"Time stepping/End time=0.02",
           "Output/Interval=0.005",
           "Output/Time series interval=0"},
          {stop_after_one_step, stop_after_one_step, to_the_end});

  compare("oedometer, quasi-static",
          prm + "oedometer.prm",
          {},
          {stop_after_one_step,
           stop_after_one_step,
           stop_after_one_step,
           to_the_end});

  // End time is raised in the last part; the first End time is on the
  // output interval, since a run that ends writes a snapshot there.
  const std::vector<std::string> disk = {"Time stepping/End time=0.02",
                                         "Output/Interval=0.004"};
  compare("rolling_disk_MPM, Newmark with walls, End time raised",
          prm + "rolling_disk.prm",
          disk,
          {stop_after_one_step,
           {"Time stepping/End time=0.008",
            "Checkpoint/Wall time interval=1e-9"},
           to_the_end});

  // rolling_disk.prm steps by 2e-3 s to 0.01 s: after one step, halving
  // applies at once.
  changed_steps("rolling disk, Newmark, Time step halved at the restart",
                prm + "rolling_disk.prm",
                {"Time stepping/End time=0.01"},
                "Time stepping/Time step=1e-3",
                {2e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3});
  // The velocity projection is made anew at every step: a continued run
  // may change it (and so continue checkpoints from before the entry).
  changed_steps("free fall, explicit, Velocity projection changed at the "
                "restart",
                mpm_tests::source_file("scenes/free_fall.prm"),
                {"Time stepping/End time=0.02"},
                "Time stepping/Velocity projection=corrected",
                {5e-3, 5e-3, 5e-3, 5e-3});
  // A checkpoint written before an entry was declared continues when the
  // entry is at its default (it keeps the behaviour of the older mpm), and
  // is refused when the scene sets another value.
  deallog << "--- a checkpoint that lacks an entry" << std::endl;
  const std::vector<std::string> fall = {"Time stepping/End time=0.02"};
  const std::string free_fall = mpm_tests::source_file("scenes/free_fall.prm");
  mpm_tests::check(
    "without Adaptive grid/Finer levels, at its default: continued, exit 0",
    continue_without_entry(free_fall, fall, "Adaptive grid/Finer levels") ==
      0);
  mpm_tests::check(
    "without Materials/soft/Young's modulus, which the scene sets: "
    "refused, exit 2",
    continue_without_entry(free_fall, fall, "Materials/soft/Young's modulus") ==
      2);

  // oedometer.prm: 10 load steps over End time 1. With 5, the step of 0.1
  // grows by doubling to 0.2.
  changed_steps("oedometer, quasi-static, Load steps halved at the restart",
                prm + "oedometer.prm",
                {},
                "Time stepping/Load steps=5",
                {0.1, 0.1, 0.2, 0.2, 0.2, 0.2});

  // The floor ends after the second step (the third part starts without
  // it), and the block leaves through the outflow boundary from about
  // 0.05 s on, so the last part starts with mass removed: the parts must
  // find the walls in force at their time and carry the removed mass on.
  // A fixed step, so that the third part's End time is on the steps.
  compare("opening floor, a wall that ends and an outflow",
          mpm_tests::source_file("scenes/opening_floor.prm"),
          {"Boundary conditions/Fixed boundaries=bottom until 0.0006",
           "Time stepping/End time=0.3",
           "Time stepping/Time step=4e-4",
           "Output/Interval=0.05"},
          {stop_after_one_step,
           stop_after_one_step,
           {"Time stepping/End time=0.1",
            "Checkpoint/Wall time interval=1e-9"},
           to_the_end});

  // Releases of an inflow before, between and after the parts (an empty
  // grid until 0.002 s, releases at 0.002, 0.152 and 0.302 s), with the
  // density from the point positions: the parts must release what the
  // straight run does, when it does, with the same ids.
  compare("inflow, releases across the parts",
          mpm_tests::source_file("scenes/inflow.prm"),
          {"Bodies/portion/First release=0.002",
           "Bodies/portion/Release interval=0.15",
           "Materials/fill/Wieckowski granular/Density from positions=true",
           "Time stepping/End time=0.35",
           "Time stepping/Time step=1e-3",
           "Output/Interval=0.05"},
          {stop_after_one_step,
           stop_after_one_step,
           {"Time stepping/End time=0.2",
            "Checkpoint/Wall time interval=1e-9"},
           to_the_end});

  // The meshfree methods: on two ranks the continued run builds its node
  // cloud on the partition of the start, not the one it continues on.
  for (const std::string method : {"GMM-MLS", "GMM-LME"})
      {
        std::vector<std::string> settings = disk;
        settings.push_back("Method=" + method);
        settings.push_back("Time stepping/End time=0.01");
        compare("rolling_disk_" + method + ", Newmark with walls",
                prm + "rolling_disk.prm",
                settings,
                {stop_after_one_step, stop_after_one_step, to_the_end});
      }
}
