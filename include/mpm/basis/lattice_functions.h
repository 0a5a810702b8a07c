#ifndef mpm_basis_lattice_functions_h
#define mpm_basis_lattice_functions_h

#include <mpm/basis/grid_functions.h>
#include <mpm/basis/node_lattice.h>
#include <mpm/grid/grid.h>

#include <array>
#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * One direction of a smooth support: for the lattice nodes corner - 1 +
   * k, k = 0..3, the value and the derivative (per cell length) of their
   * function at a point whose lattice coordinate is x (in cells, between 0
   * and n).
   */
  struct LatticeWeights
  {
    std::array<double, 4> value;
    std::array<double, 4> slope;
  };



  /**
   * What the smooth kinds (GIMP, B-splines) share: tensor products of 1D
   * functions on the grid's node lattice (NodeLattice), which reach the
   * nodes of the cells around the point's cell (at most 3 per direction)
   * and need a grid of equal axis-aligned cells filling a box. A kind gives
   * the 1D values and slopes per direction (weights()); this class builds
   * the support from them.
   */
  template <int dim>
  class LatticeFunctions : public GridFunctions<dim>
  {
  public:
    using Weights1D = LatticeWeights;

    void
    evaluate(const unsigned int             active_cell_index,
             const Point<dim> &             reference_point,
             const ArrayView<const double> &p,
             Support<dim> &                 support) const override;

    bool
    reaches_neighbours() const override
    {
      return true;
    }

    const NodeLattice<dim> *
    lattice() const override
    {
      return &node_lattice;
    }

  protected:
    /**
     * The lattice of `grid`; a grid that is not a lattice of equal boxes is
     * refused with a message naming `entry` (InputError).
     */
    LatticeFunctions(const Grid<dim> &grid, const std::string &entry)
      : node_lattice(grid, entry)
    {}

    /**
     * Per direction, the 1D functions at a point of lattice coordinates x
     * (x[d] in cells from the grid's lower corner) in the cell whose lower
     * corner is the lattice node `corner`, for a point with properties p.
     */
    virtual std::array<Weights1D, dim>
    weights(const Point<dim> &                  x,
            const std::array<int, dim> &        corner,
            const ArrayView<const double> &     p) const = 0;

    NodeLattice<dim> node_lattice;
  };
} // namespace mpm

#endif
