#ifndef mpm_basis_grid_basis_h
#define mpm_basis_grid_basis_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/basis/support.h>
#include <mpm/grid/grid.h>

#include <array>
#include <cmath>

namespace mpm
{
  using namespace dealii;

  /**
   * Q1 shape functions of the background cell that holds a point, evaluated
   * from the point's reference coordinates. Evaluating through FEValues at
   * every point is slow; here the Grid's cached node ids and vertices of the
   * cell give a support in a few dozen flops: the tensor-product values,
   * and the gradients through the inverse Jacobian of the bilinear
   * (trilinear) cell map, which is diagonal on axis-aligned cells.
   */
  template <int dim>
  class GridBasis
  {
  public:
    static constexpr unsigned int n_vertices = Grid<dim>::n_vertices;

    explicit GridBasis(const Grid<dim> &grid)
      : grid(grid)
    {}

    void
    evaluate(const unsigned int active_cell_index,
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
     * The integrals of the cell's shape functions, int_c N_v dV, by the
     * 2^dim-point Gauss rule (exact on bilinear cells): V/4 on a 2D
     * parallelogram.
     */
    void
    nodal_volumes(const unsigned int              active_cell_index,
                  std::array<double, n_vertices> &volumes) const
    {
      const double offset = 0.5 / std::sqrt(3.);
      volumes.fill(0.);
      std::array<double, n_vertices>         values;
      std::array<Tensor<1, dim>, n_vertices> grad_ref;
      for (unsigned int q = 0; q < n_vertices; ++q)
        {
          Point<dim> xi;
          for (unsigned int d = 0; d < dim; ++d)
            xi[d] = (q & (1u << d)) ? 0.5 + offset : 0.5 - offset;
          reference_values(xi, values, grad_ref);
          const double weight =
            determinant(jacobian(grid.cell_geometry(active_cell_index),
                                 grad_ref)) /
            n_vertices;
          for (unsigned int v = 0; v < n_vertices; ++v)
            volumes[v] += weight * values[v];
        }
    }

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

    static Tensor<2, dim>
    jacobian(const CellGeometry &                          cell,
             const std::array<Tensor<1, dim>, n_vertices> &grad_ref)
    {
      Tensor<2, dim> J;
      for (unsigned int v = 0; v < n_vertices; ++v)
        J += outer_product(cell.vertices[v], grad_ref[v]);
      return J;
    }

    const Grid<dim> &grid;
  };
} // namespace mpm

#endif
