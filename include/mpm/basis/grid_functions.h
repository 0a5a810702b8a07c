#ifndef mpm_basis_grid_functions_h
#define mpm_basis_grid_functions_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/point.h>
#include <deal.II/fe/fe.h>

#include <mpm/basis/node_lattice.h>
#include <mpm/basis/support.h>

#include <memory>

namespace mpm
{
  using namespace dealii;

  /**
   * One kind of MPM shape functions on the background grid (Q1, GIMP,
   * B-splines; GridBasis builds the one a scene names): what a point's
   * support is, what each function integrates to over a cell, and the
   * finite element whose degrees of freedom are the kind's nodes, for the
   * implicit schemes' unknowns. A new kind (a simplex basis, say) is one
   * more class of this interface.
   */
  template <int dim>
  class GridFunctions
  {
  public:
    virtual ~GridFunctions() = default;

    /**
     * The support of a point in a locally owned cell, at `reference_point`
     * in it, with properties `p` (GIMP reads the point's size and F).
     */
    virtual void
    evaluate(const unsigned int             active_cell_index,
             const Point<dim> &             reference_point,
             const ArrayView<const double> &p,
             Support<dim> &                 support) const = 0;

    /**
     * The integrals over a locally owned cell of every shape function that
     * reaches into it, int_c N_i dV, exactly: the nodes in
     * `integrals.nodes`, the integrals in `integrals.N`.
     */
    virtual void
    cell_integrals(const unsigned int active_cell_index,
                   Support<dim> &     integrals) const = 0;

    /** Whether a point's support reaches beyond its cell. */
    virtual bool
    reaches_neighbours() const = 0;

    /** The lattice of a kind that reaches beyond the cell, else nullptr. */
    virtual const NodeLattice<dim> *
    lattice() const
    {
      return nullptr;
    }

    /**
     * The scalar finite element whose degrees of freedom sit at the kind's
     * nodes: the grid's vertices, FE_Q(1), for every kind so far.
     */
    virtual std::unique_ptr<FiniteElement<dim>>
    node_element() const;
  };
} // namespace mpm

#endif
