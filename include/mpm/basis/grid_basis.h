#ifndef mpm_basis_grid_basis_h
#define mpm_basis_grid_basis_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/distributed/tria.h>

#include <mpm/assembly/grid_nodes.h>
#include <mpm/basis/support.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Q1 shape functions of the background cell that holds a point, evaluated
   * from the point's reference coordinates. Evaluating through FEValues at
   * every point is slow; here a cell's node indices and geometry are cached
   * once, and a support costs a few dozen flops: the tensor-product values,
   * and the gradients through the inverse Jacobian of the bilinear
   * (trilinear) cell map, which is diagonal on axis-aligned cells.
   */
  template <int dim>
  class GridBasis
  {
  public:
    static constexpr unsigned int n_vertices = 1u << dim;

    /** Cache node indices and geometry of every locally owned cell. */
    void
    reinit(const GridNodes<dim> &nodes);

    /** True if every cell of the grid is an axis-aligned box. */
    bool
    grid_is_cartesian() const
    {
      return all_cells_cartesian;
    }

    /** Smallest edge of any cell, over all ranks. */
    double
    minimum_cell_size() const
    {
      return min_cell_size;
    }

    /** Smallest edge of the cell with this active index. */
    double
    cell_size(const unsigned int active_cell_index) const
    {
      return cells[active_cell_index].min_edge;
    }

    void
    evaluate(const unsigned int active_cell_index,
             const Point<dim> & reference_point,
             Support<dim> &     support) const
    {
      const CellData &cell = cells[active_cell_index];
      support.n_nodes      = n_vertices;
      support.spacing      = cell.min_edge;

      std::array<Tensor<1, dim>, n_vertices> grad_ref;
      for (unsigned int v = 0; v < n_vertices; ++v)
        {
          double value = 1.;
          for (unsigned int d = 0; d < dim; ++d)
            value *=
              (v & (1u << d)) ? reference_point[d] : 1. - reference_point[d];
          support.N[v] = value;
          for (unsigned int k = 0; k < dim; ++k)
            {
              double g = (v & (1u << k)) ? 1. : -1.;
              for (unsigned int d = 0; d < dim; ++d)
                if (d != k)
                  g *= (v & (1u << d)) ? reference_point[d] :
                                         1. - reference_point[d];
              grad_ref[v][k] = g;
            }
          support.nodes[v] = cell.nodes[v];
        }

      if (cell.is_cartesian)
        {
          for (unsigned int v = 0; v < n_vertices; ++v)
            for (unsigned int k = 0; k < dim; ++k)
              support.grad_N[v][k] = grad_ref[v][k] * cell.inverse_h[k];
        }
      else
        {
          Tensor<2, dim> jacobian;
          for (unsigned int v = 0; v < n_vertices; ++v)
            jacobian += outer_product(cell.vertices[v], grad_ref[v]);
          const Tensor<2, dim> inverse_transpose =
            transpose(invert(jacobian));
          for (unsigned int v = 0; v < n_vertices; ++v)
            support.grad_N[v] = inverse_transpose * grad_ref[v];
        }
    }

  private:
    struct CellData
    {
      std::array<unsigned int, n_vertices> nodes;
      std::array<Tensor<1, dim>, n_vertices> vertices;
      Tensor<1, dim>                         inverse_h;
      double                                 min_edge     = 0.;
      bool                                   is_cartesian = false;
    };

    /** Indexed by active cell index; only locally owned entries are set. */
    std::vector<CellData> cells;
    bool                  all_cells_cartesian = true;
    double                min_cell_size       = 0.;
  };
} // namespace mpm

#endif
