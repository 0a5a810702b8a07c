#ifndef mpm_basis_linear_functions_h
#define mpm_basis_linear_functions_h

#include <mpm/basis/grid_functions.h>
#include <mpm/grid/grid.h>

#include <array>

namespace mpm
{
  using namespace dealii;

  /**
   * Q1 (Grid/Shape functions = linear): the nodes of the point's cell, from
   * its reference coordinates and the Grid's cached cell geometry in a few
   * dozen flops: tensor-product values, gradients through the inverse
   * Jacobian of the bilinear (trilinear) cell map, which is diagonal on
   * axis-aligned cells. Any grid.
   *
   * On an adaptive grid the functions are those of the conforming grid: a
   * vertex that hangs on a coarser neighbour's face passes its value to
   * that face's nodes (Grid::hanging_vertices), so a point's support may
   * reach nodes of the coarser cell.
   *
   * evaluate() is defined here, so that a caller that holds this class
   * (GridBasis) calls it without a virtual call, inlined.
   */
  template <int dim>
  class LinearFunctions final : public GridFunctions<dim>
  {
  public:
    static constexpr unsigned int n_vertices = Grid<dim>::n_vertices;

    explicit LinearFunctions(const Grid<dim> &grid)
      : grid(grid)
    {}

    void
    evaluate(const unsigned int active_cell_index,
             const Point<dim> & reference_point,
             const ArrayView<const double> &,
             Support<dim> &support) const override
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
     * The hats' integrals: the 2^dim-point Gauss rule of the bilinear cell,
     * V/4 per node on a 2D parallelogram.
     */
    void
    cell_integrals(const unsigned int active_cell_index,
                   Support<dim> &     integrals) const override;

    bool
    reaches_neighbours() const override
    {
      return false;
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

  private:
    using CellGeometry = typename Grid<dim>::CellGeometry;

    /**
     * On a cell with hanging vertices (an adaptive grid), give each hanging
     * vertex's value and gradient to its masters: the support is then that
     * of the continuous Q1 functions of the refined grid, a partition of
     * unity that reproduces linear fields, and no point reaches a hanging
     * node. `support` holds the cell's vertices in order on entry.
     */
    void
    condense_hanging_vertices(const CellGeometry &cell,
                              Support<dim> &      support) const;

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

    const Grid<dim> &grid;
  };
} // namespace mpm

#endif
