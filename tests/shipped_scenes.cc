// Every scene shipped in prm/ sets up and runs its first steps, as a user
// would start it (`mpm prm/<scene>.prm`), so that no example is broken:
// the explicit scenes for 1 % of their End time, the Newmark scenes for
// three time steps, the quasi-static ones whole (they take seconds). Each
// must exit with 0 and reach the shortened End time. The scenes are found
// in the directory, so a new scene is tested without changing this file.

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <iomanip>
#include <sstream>

#include "tests.h"

using namespace dealii;

namespace
{
  /** The value of `set <entry> = ...` in a prm file, or `fallback`. */
  std::string
  entry_of(const std::string &text,
           const std::string &entry,
           const std::string &fallback)
  {
    std::smatch found;
    if (std::regex_search(text,
                          found,
                          std::regex("\\n\\s*set\\s+" + entry +
                                     "\\s*=\\s*([^#\\n]*[^#\\s])")))
      return found[1];
    return fallback;
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  std::vector<std::string> scenes;
  for (const auto &file :
       std::filesystem::directory_iterator(mpm_tests::source_file("../prm")))
    if (file.path().extension() == ".prm")
      scenes.push_back(file.path().filename().string());
  std::sort(scenes.begin(), scenes.end());

  for (const std::string &scene : scenes)
    {
      std::ifstream      in(mpm_tests::source_file("../prm/" + scene));
      std::ostringstream text;
      text << '\n' << in.rdbuf();
      const std::string scheme = entry_of(text.str(), "Scheme", "explicit");
      double end_time = std::stod(entry_of(text.str(), "End time", "1"));
      if (scheme == "explicit")
        end_time /= 100.;
      else if (scheme == "Newmark")
        end_time = 3. * std::stod(entry_of(text.str(), "Time step", "0"));
      std::ostringstream end;
      end << std::setprecision(17) << end_time;

      std::string screen;
      int         code = -1;
      auto        csv  = mpm_tests::run_scene("../prm/" + scene,
                                      "output-" + scene,
                                      {"Time stepping/End time=" + end.str()},
                                      &screen,
                                      &code);
      mpm_tests::check(scene + " (" + scheme + "): runs to its shortened End "
                         "time and exits with 0",
                       code == 0 && csv["time"].size() > 2 &&
                         std::abs(csv["time"].back() - end_time) <
                           1e-9 * end_time);
    }
}
