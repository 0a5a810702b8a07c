#ifndef mpm_basis_grid_basis_h
#define mpm_basis_grid_basis_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
#include <mpm/basis/grid_functions.h>
#include <mpm/basis/linear_functions.h>
#include <mpm/basis/node_lattice.h>
#include <mpm/basis/support.h>
#include <mpm/grid/grid.h>
#include <mpm/points/point_layout.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>

namespace mpm
{
  using namespace dealii;

  /** The shape functions of MPM on the background grid (Grid/Shape functions). */
  enum class GridShapeFunctions
  {
    /** Q1: the nodes of the point's cell, cell-crossing noise and all. */
    linear,
    /** GIMP with the point's domain fixed at its initial size. */
    uGIMP,
    /** GIMP with the point's domain stretched by the diagonal of F. */
    cpGIMP,
    /** Quadratic B-splines centred on the nodes. */
    quadratic_bspline
  };

  /**
   * The shape functions of MPM on the background grid, evaluated at a
   * material point: a Support for the assembly, whatever the kind. Each
   * kind is a class of its own behind the interface GridFunctions:
   * LinearFunctions (Q1, any grid), GimpFunctions (uGIMP, cpGIMP) and
   * BsplineFunctions (quadratic B-splines), the smooth ones on the grid's
   * NodeLattice. This class parses the kind, builds it, and calls Q1
   * directly (the most used kind, whose evaluation is a few dozen flops)
   * and the others through the interface.
   */
  template <int dim>
  class GridBasis
  {
  public:
    /** `Grid/Shape functions`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /** The kind the scene asks for (the handler is at top level). */
    static GridShapeFunctions
    parse_kind(ParameterHandler &prm);

    /** The prm name of a kind. */
    static std::string
    name(const GridShapeFunctions kind);

    /**
     * The grid's shape functions other than linear are MPM's: the meshfree
     * methods take their own (InputError).
     */
    static void
    check_scene(const SceneChoices &choices, const GridShapeFunctions kind)
    {
      if (kind != GridShapeFunctions::linear && choices.meshfree())
        throw InputError("Grid/Shape functions = " + name(kind) +
                         " are MPM's; with Method = " + choices.method +
                         " the shape functions are the meshfree ones (leave "
                         "Shape functions at linear).");
    }

    /**
     * Shape functions of `kind` on `grid`; a smooth kind refuses a grid
     * that is not a lattice of equal boxes (InputError).
     */
    explicit GridBasis(const Grid<dim> &        grid,
                       const GridShapeFunctions kind =
                         GridShapeFunctions::linear);

    /** It points into itself (linear). */
    GridBasis(const GridBasis &) = delete;
    GridBasis &
    operator=(const GridBasis &) = delete;

    GridShapeFunctions
    kind() const
    {
      return shape_functions;
    }

    /** The lattice of a smooth kind (reaches_neighbours()). */
    const NodeLattice<dim> &
    node_lattice() const
    {
      Assert(functions && functions->lattice(), ExcInternalError());
      return *functions->lattice();
    }

    /** Whether a point's support reaches beyond its cell. */
    bool
    reaches_neighbours() const
    {
      return linear == nullptr && functions->reaches_neighbours();
    }

    /**
     * The support of a point in a locally owned cell, at `reference_point`
     * in it, with properties `p` (GIMP reads the point's size and F).
     */
    void
    evaluate(const unsigned int             active_cell_index,
             const Point<dim> &             reference_point,
             const ArrayView<const double> &p,
             Support<dim> &                 support) const
    {
      if (linear != nullptr)
        linear->evaluate(active_cell_index, reference_point, p, support);
      else
        functions->evaluate(active_cell_index, reference_point, p, support);
    }

    /**
     * det J of the cell map at a reference point: the volume a point there
     * stands for, per unit reference volume.
     */
    double
    volume_factor(const unsigned int active_cell_index,
                  const Point<dim> & reference_point) const
    {
      return linear_functions.volume_factor(active_cell_index, reference_point);
    }

    /**
     * The integrals over a locally owned cell of every shape function that
     * reaches into it, int_c N_i dV, exactly: the nodes in
     * `integrals.nodes`, the integrals in `integrals.N`. For Q1 and GIMP
     * (whose grid functions are the hats) the 2^dim-point Gauss rule of
     * the bilinear cell, V/4 per node on a 2D parallelogram; for
     * B-splines two Gauss points on each half cell per direction.
     */
    void
    cell_integrals(const unsigned int active_cell_index,
                   Support<dim> &     integrals) const
    {
      if (linear != nullptr)
        linear->cell_integrals(active_cell_index, integrals);
      else
        functions->cell_integrals(active_cell_index, integrals);
    }

    /**
     * The scalar finite element whose degrees of freedom sit at the
     * basis's nodes, for the implicit schemes' unknowns.
     */
    std::unique_ptr<FiniteElement<dim>>
    node_element() const
    {
      return linear != nullptr ? linear->node_element() :
                                 functions->node_element();
    }

  private:
    const GridShapeFunctions shape_functions;
    /** Q1, the cell map's volume factor for every kind. */
    const LinearFunctions<dim> linear_functions;
    /** &linear_functions if the kind is linear, else nullptr. */
    const LinearFunctions<dim> *linear = nullptr;
    /** A kind other than linear. */
    std::unique_ptr<const GridFunctions<dim>> functions;
  };
} // namespace mpm

#endif
