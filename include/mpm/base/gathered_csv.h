#ifndef mpm_base_gathered_csv_h
#define mpm_base_gathered_csv_h

#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /** `directory/name_<step, six digits>.csv`. */
  inline std::string
  step_csv_name(const std::string &directory,
                const std::string &name,
                const unsigned int step)
  {
    std::ostringstream file;
    file << directory << "/" << name << "_" << std::setw(6)
         << std::setfill('0') << step << ".csv";
    return file.str();
  }

  /** "x,y," (2D) or "x,y,z,": the first columns of a file of positions. */
  template <int dim>
  std::string
  coordinate_columns()
  {
    return std::string("x,y,z,").substr(0, 2 * dim);
  }

  /**
   * Write rows that the ranks hold between them into one CSV file: rank 0
   * gathers them, sorts them (so that the file does not depend on the
   * number of ranks) and writes `header` and the rows. Collective; every
   * rank throws RunError if the file cannot be written.
   */
  template <std::size_t n>
  void
  write_gathered_csv(const MPI_Comm                            comm,
                     const std::vector<std::array<double, n>> &rows,
                     const std::string &                       filename,
                     const std::string &                       header)
  {
    const auto gathered = Utilities::MPI::gather(comm, rows, 0);
    bool       failed   = false;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::vector<std::array<double, n>> all;
        for (const auto &part : gathered)
          all.insert(all.end(), part.begin(), part.end());
        std::sort(all.begin(), all.end());
        std::ofstream file(filename);
        file << header << '\n' << std::setprecision(12);
        for (const auto &row : all)
          for (std::size_t c = 0; c < n; ++c)
            file << row[c] << (c + 1 < n ? ',' : '\n');
        failed = !file;
      }
    if (Utilities::MPI::logical_or(failed, comm))
      throw RunError("Cannot write '" + filename + "'.");
  }
} // namespace mpm

#endif
