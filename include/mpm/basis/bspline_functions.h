#ifndef mpm_basis_bspline_functions_h
#define mpm_basis_bspline_functions_h

#include <mpm/basis/lattice_functions.h>

namespace mpm
{
  using namespace dealii;

  /**
   * Quadratic B-splines (Grid/Shape functions = quadratic B-spline), one
   * per node, C1 across cell faces; in the half cell next to a grid face
   * the two nearest nodes' functions are linear (1 - s and s), which joins
   * the quadratics with continuous values and slopes, keeps the partition
   * of unity and linear reproduction, and makes the face node interpolate
   * (N = 1 on the face), so walls hold nodes as they do with Q1.
   */
  template <int dim>
  class BsplineFunctions final : public LatticeFunctions<dim>
  {
  public:
    explicit BsplineFunctions(const Grid<dim> &grid)
      : LatticeFunctions<dim>(grid, "Grid/Shape functions = quadratic B-spline")
    {}

    /** Two Gauss points on each half cell per direction, exact. */
    void
    cell_integrals(const unsigned int active_cell_index,
                   Support<dim> &     integrals) const override;

  private:
    std::array<LatticeWeights, dim>
    weights(const Point<dim> &            x,
            const std::array<int, dim> &  corner,
            const ArrayView<const double> &) const override;
  };
} // namespace mpm

#endif
