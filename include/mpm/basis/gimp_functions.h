#ifndef mpm_basis_gimp_functions_h
#define mpm_basis_gimp_functions_h

#include <mpm/basis/lattice_functions.h>
#include <mpm/basis/linear_functions.h>
#include <mpm/points/point_layout.h>

namespace mpm
{
  using namespace dealii;

  /**
   * GIMP (Grid/Shape functions = uGIMP, cpGIMP; Bardenhagen and Kober
   * 2004; Wallstedt and Guilkey 2008): the hat functions averaged over the
   * point's domain, a box of half-width l_d = min(size_d / 2, h_d / 2) per
   * direction (size: the box the point stood for when seeded; cpGIMP
   * stretches it by F_dd); value (1 / 2l) int N dx and gradient (N(x + l) -
   * N(x - l)) / 2l. Next to a grid face the first cell's linear functions
   * go on beyond it, so a domain that reaches out still sees a partition of
   * unity that reproduces linear fields.
   */
  template <int dim>
  class GimpFunctions final : public LatticeFunctions<dim>
  {
  public:
    /** `stretched`: cpGIMP, the domain follows the diagonal of F. */
    GimpFunctions(const Grid<dim> &grid, const bool stretched)
      : LatticeFunctions<dim>(grid,
                              stretched ? "Grid/Shape functions = cpGIMP" :
                                          "Grid/Shape functions = uGIMP")
      , stretched(stretched)
      , hats(grid)
    {}

    /** The hats' integrals, as Q1's. */
    void
    cell_integrals(const unsigned int active_cell_index,
                   Support<dim> &     integrals) const override
    {
      hats.cell_integrals(active_cell_index, integrals);
    }

  private:
    std::array<LatticeWeights, dim>
    weights(const Point<dim> &             x,
            const std::array<int, dim> &   corner,
            const ArrayView<const double> &p) const override;

    const bool                 stretched;
    const LinearFunctions<dim> hats;
  };
} // namespace mpm

#endif
