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

    /**
     * Smallest edge of any cell, over all ranks: the length that limits the
     * time step and the distance a point may move in one.
     */
    double
    minimum_cell_size() const
    {
      return min_cell_size;
    }

    void
    evaluate(const unsigned int active_cell_index,
             const Point<dim> & reference_point,
             Support<dim> &     support) const
    {
      const CellData &cell = cells[active_cell_index];
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
    }

    /** GridNodes index of vertex v of a locally owned cell. */
    unsigned int
    node_of(const unsigned int active_cell_index, const unsigned int v) const
    {
      return cells[active_cell_index].nodes[v];
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
      return determinant(jacobian(cells[active_cell_index], grad_ref));
    }

  private:
    struct CellData;

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

    static Tensor<2, dim>
    jacobian(const CellData &                              cell,
             const std::array<Tensor<1, dim>, n_vertices> &grad_ref)
    {
      Tensor<2, dim> J;
      for (unsigned int v = 0; v < n_vertices; ++v)
        J += outer_product(cell.vertices[v], grad_ref[v]);
      return J;
    }

    struct CellData
    {
      std::array<unsigned int, n_vertices> nodes;
      std::array<Tensor<1, dim>, n_vertices> vertices;
      Tensor<1, dim>                         inverse_h;
      bool                                   is_cartesian = false;
    };

    /** Indexed by active cell index; only locally owned entries are set. */
    std::vector<CellData> cells;
    bool                  all_cells_cartesian = true;
    double                min_cell_size       = 0.;
  };
} // namespace mpm

#endif
