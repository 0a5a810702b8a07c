#ifndef mpm_base_shared_position_h
#define mpm_base_shared_position_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <algorithm>
#include <array>
#include <sstream>
#include <string>
#include <utility>

namespace mpm
{
  using namespace dealii;

  /** Lexicographic order of points, to pick one of several alike. */
  template <int dim>
  bool
  lexicographically_less(const Point<dim> &a, const Point<dim> &b)
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (a[d] != b[d])
        return a[d] < b[d];
    return false;
  }

  /**
   * For error messages that every rank throws alike, whatever the number of
   * ranks: the lexicographically smallest of the positions held by the
   * ranks with `has_position`, formatted as "(x, y)", and the rank that
   * holds it. Collective.
   */
  template <int dim>
  std::pair<std::string, unsigned int>
  shared_position_and_rank(const bool        has_position,
                           const Point<dim> &position,
                           const MPI_Comm    comm)
  {
    std::array<double, dim + 1> mine;
    mine[0] = has_position ? 1. : 0.;
    for (unsigned int d = 0; d < dim; ++d)
      mine[d + 1] = position[d];
    bool         found = false;
    Point<dim>   best;
    unsigned int best_rank = 0;
    const auto   all       = Utilities::MPI::all_gather(comm, mine);
    for (unsigned int rank = 0; rank < all.size(); ++rank)
      if (all[rank][0] == 1.)
        {
          Point<dim> p;
          for (unsigned int d = 0; d < dim; ++d)
            p[d] = all[rank][d + 1];
          if (!found || lexicographically_less(p, best))
            {
              best      = p;
              best_rank = rank;
            }
          found = true;
        }
    std::ostringstream s;
    s << "(";
    for (unsigned int d = 0; d < dim; ++d)
      s << (d ? ", " : "") << best[d];
    s << ")";
    return {s.str(), best_rank};
  }

  /** The position alone, see shared_position_and_rank(). */
  template <int dim>
  std::string
  shared_position(const bool        has_position,
                  const Point<dim> &position,
                  const MPI_Comm    comm)
  {
    return shared_position_and_rank(has_position, position, comm).first;
  }
} // namespace mpm

#endif
