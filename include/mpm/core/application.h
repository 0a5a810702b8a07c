#ifndef mpm_core_application_h
#define mpm_core_application_h

#include <string>
#include <vector>

namespace mpm
{
  /**
   * The `mpm` command line: `mpm [--set Section/entry=value]... scene.prm`,
   * `mpm --print-parameters`, `mpm --help`. Returns the exit code; errors
   * are printed to std::cerr on rank 0 as one message. MPI must be
   * initialised by the caller.
   */
  int
  run_command_line(const std::vector<std::string> &arguments);
} // namespace mpm

#endif
