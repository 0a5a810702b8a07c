#ifndef mpm_basis_grid_basis_h
#define mpm_basis_grid_basis_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
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
   * material point: a Support for the assembly, whatever the kind.
   *
   * - linear (Q1): the nodes of the point's cell, from its reference
   *   coordinates and the Grid's cached cell geometry in a few dozen
   *   flops: tensor-product values, gradients through the inverse Jacobian
   *   of the bilinear (trilinear) cell map, which is diagonal on
   *   axis-aligned cells. Any grid.
   * - uGIMP, cpGIMP (Bardenhagen and Kober 2004; Wallstedt and Guilkey
   *   2008): the hat functions averaged over the point's domain, a box of
   *   half-width l_d = min(size_d / 2, h_d / 2) per direction (size: the
   *   box the point stood for when seeded; cpGIMP stretches it by F_dd);
   *   value (1 / 2l) int N dx and gradient (N(x + l) - N(x - l)) / 2l. Next
   *   to a grid face the first cell's linear functions go on beyond it, so
   *   a domain that reaches out still sees a partition of unity that
   *   reproduces linear fields.
   * - quadratic B-splines, one per node, C1 across cell faces; in the half
   *   cell next to a grid face the two nearest nodes' functions are linear
   *   (1 - s and s), which joins the quadratics with continuous values and
   *   slopes, keeps the partition of unity and linear reproduction, and
   *   makes the face node interpolate (N = 1 on the face), so walls hold
   *   nodes as they do with Q1.
   *
   * On an adaptive grid the linear functions are those of the conforming
   * grid: a vertex that hangs on a coarser neighbour's face passes its
   * value to that face's nodes (Grid::hanging_vertices), so a point's
   * support may reach nodes of the coarser cell.
   *
   * The smooth kinds reach the nodes of the cells around the point's cell
   * (at most 3 per direction) and need a grid of equal axis-aligned cells
   * filling a box (NodeLattice).
   */
  template <int dim>
  class GridBasis
  {
  public:
    static constexpr unsigned int n_vertices = Grid<dim>::n_vertices;

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

    GridShapeFunctions
    kind() const
    {
      return shape_functions;
    }

    /** The lattice of a smooth kind (reaches_neighbours()). */
    const NodeLattice<dim> &
    node_lattice() const
    {
      Assert(lattice, ExcInternalError());
      return *lattice;
    }

    /** Whether a point's support reaches beyond its cell. */
    bool
    reaches_neighbours() const
    {
      return shape_functions != GridShapeFunctions::linear;
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
      if (shape_functions == GridShapeFunctions::linear)
        evaluate_linear(active_cell_index, reference_point, support);
      else
        evaluate_smooth(active_cell_index,
                        reference_point,
                        domain_half_width(p),
                        support);
    }

    /**
     * det J of the cell map at a reference point: the volume a point there
     * stands for, per unit reference volume.
     */
    double
    volume_factor(const unsigned int active_cell_index,
                  const Point<dim> & reference_point) const
    {
      std::array<double, n_vertices>         values;
      std::array<Tensor<1, dim>, n_vertices> grad_ref;
      reference_values(reference_point, values, grad_ref);
      return determinant(
        jacobian(grid.cell_geometry(active_cell_index), grad_ref));
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
                   Support<dim> &     integrals) const;

  private:
    void
    evaluate_linear(const unsigned int active_cell_index,
                    const Point<dim> & reference_point,
                    Support<dim> &     support) const
    {
      const CellGeometry &cell = grid.cell_geometry(active_cell_index);
      support.resize(n_vertices);
      std::array<double, n_vertices>         values;
      std::array<Tensor<1, dim>, n_vertices> grad_ref;
      reference_values(reference_point, values, grad_ref);
      for (unsigned int v = 0; v < n_vertices; ++v)
        {
          support.nodes[v] = cell.nodes[v];
          support.N[v]     = values[v];
        }

      if (cell.is_cartesian)
        {
          for (unsigned int v = 0; v < n_vertices; ++v)
            for (unsigned int k = 0; k < dim; ++k)
              support.grad_N[v][k] = grad_ref[v][k] * cell.inverse_h[k];
        }
      else
        {
          const Tensor<2, dim> inverse_transpose =
            transpose(invert(jacobian(cell, grad_ref)));
          for (unsigned int v = 0; v < n_vertices; ++v)
            support.grad_N[v] = inverse_transpose * grad_ref[v];
        }
      if (cell.n_hanging > 0)
        condense_hanging_vertices(cell, support);
    }

    /**
     * On a cell with hanging vertices (an adaptive grid), give each hanging
     * vertex's value and gradient to its masters: the support is then that
     * of the continuous Q1 functions of the refined grid, a partition of
     * unity that reproduces linear fields, and no point reaches a hanging
     * node. `support` holds the cell's vertices in order on entry.
     */
    void
    condense_hanging_vertices(const typename Grid<dim>::CellGeometry &cell,
                              Support<dim> &support) const;

    /**
     * GIMP: the half-width of the point's domain in cells per direction,
     * at most 1/2, so that it reaches at most three nodes per direction;
     * zero for B-splines.
     */
    Tensor<1, dim>
    domain_half_width(const ArrayView<const double> &p) const
    {
      using Layout = PointLayout<dim>;
      Tensor<1, dim> l;
      if (shape_functions == GridShapeFunctions::quadratic_bspline)
        return l;
      for (unsigned int d = 0; d < dim; ++d)
        {
          double size = p[Layout::reference_size + d];
          if (shape_functions == GridShapeFunctions::cpGIMP)
            size *= std::abs(p[Layout::deformation_gradient + d * dim + d]);
          l[d] = std::min(0.5 * size * lattice->inverse_h()[d], 0.5);
        }
      return l;
    }

    /**
     * GIMP or B-spline support at a reference point, with the domain
     * half-widths `l` in cells (GIMP; l = 0 gives the hats themselves).
     */
    void
    evaluate_smooth(const unsigned int    active_cell_index,
                    const Point<dim> &    reference_point,
                    const Tensor<1, dim> &l,
                    Support<dim> &        support) const;

  private:
    using CellGeometry = typename Grid<dim>::CellGeometry;

    /** Q1 values and reference gradients, vertices in deal.II's order. */
    static void
    reference_values(const Point<dim> &                      xi,
                     std::array<double, n_vertices> &        values,
                     std::array<Tensor<1, dim>, n_vertices> &gradients)
    {
      for (unsigned int v = 0; v < n_vertices; ++v)
        {
          double value = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            value *= (v & (1u << d)) ? xi[d] : 1. - xi[d];
          values[v] = value;
          for (unsigned int k = 0; k < dim; ++k)
            {
              double g = (v & (1u << k)) ? 1. : -1.;
              for (unsigned int d = 0; d < dim; ++d)
                if (d != k)
                  g *= (v & (1u << d)) ? xi[d] : 1. - xi[d];
              gradients[v][k] = g;
            }
        }
    }

    Tensor<2, dim>
    jacobian(const CellGeometry &                          cell,
             const std::array<Tensor<1, dim>, n_vertices> &grad_ref) const
    {
      Tensor<2, dim> J;
      for (unsigned int v = 0; v < n_vertices; ++v)
        J += outer_product(grid.node_position(cell.nodes[v]), grad_ref[v]);
      return J;
    }

    const Grid<dim> &                  grid;
    const GridShapeFunctions           shape_functions;
    std::unique_ptr<NodeLattice<dim>> lattice;
  };
} // namespace mpm

#endif
