#ifndef mpm_core_shared_position_h
#define mpm_core_shared_position_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <algorithm>
#include <array>
#include <sstream>
#include <string>

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
   * ranks with `has_position`, formatted as "(x, y)". Collective.
   */
  template <int dim>
  std::string
  shared_position(const bool        has_position,
                  const Point<dim> &position,
                  const MPI_Comm    comm)
  {
    std::array<double, dim + 1> mine;
    mine[0] = has_position ? 1. : 0.;
    for (unsigned int d = 0; d < dim; ++d)
      mine[d + 1] = position[d];
    bool       found = false;
    Point<dim> best;
    for (const auto &other : Utilities::MPI::all_gather(comm, mine))
      if (other[0] == 1.)
        {
          Point<dim> p;
          for (unsigned int d = 0; d < dim; ++d)
            p[d] = other[d + 1];
          if (!found || lexicographically_less(p, best))
            best = p;
          found = true;
        }
    std::ostringstream s;
    s << "(";
    for (unsigned int d = 0; d < dim; ++d)
      s << (d ? ", " : "") << best[d];
    s << ")";
    return s.str();
  }
} // namespace mpm

#endif
