#ifndef mpm_core_shared_position_h
#define mpm_core_shared_position_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <sstream>
#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * For error messages that every rank throws alike: the position held by
   * the lowest rank with `has_position`, formatted as "(x, y)". Collective.
   */
  template <int dim>
  std::string
  shared_position(const bool        has_position,
                  const Point<dim> &position,
                  const MPI_Comm    comm)
  {
    const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int reporter =
      Utilities::MPI::min(has_position ? rank : n_ranks, comm);
    double where[dim] = {};
    if (rank == reporter)
      for (unsigned int d = 0; d < dim; ++d)
        where[d] = position[d];
    MPI_Allreduce(MPI_IN_PLACE, where, dim, MPI_DOUBLE, MPI_SUM, comm);
    std::ostringstream s;
    s << "(";
    for (unsigned int d = 0; d < dim; ++d)
      s << (d ? ", " : "") << where[d];
    s << ")";
    return s.str();
  }
} // namespace mpm

#endif
