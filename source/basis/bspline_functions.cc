#include <mpm/basis/bspline_functions.h>

#include <cmath>

namespace mpm
{
  namespace
  {
    /**
     * Quadratic B-splines: N(s) = 3/4 - s^2 for |s| <= 1/2, (3/2 - |s|)^2 / 2
     * for 1/2 < |s| < 3/2, s the distance to the node in cells; in the half
     * cell next to a grid face, 1 - s and s on the two nearest nodes, which
     * meet the quadratics with the same value and slope at s = 1/2.
     */
    LatticeWeights
    bspline_weights(const double x, const int corner, const int n)
    {
      LatticeWeights w;
      for (int k = 0; k < 4; ++k)
        {
          const int    i = corner - 1 + k;
          double       value = 0., slope = 0.;
          const double s = x - i;
          if (i < 0 || i > n)
            ;
          else if (x < 0.5)
            {
              // Next to the lower face: nodes 0 and 1, linear.
              if (i == 0)
                value = 1. - x, slope = -1.;
              else if (i == 1)
                value = x, slope = 1.;
            }
          else if (x > n - 0.5)
            {
              if (i == n)
                value = x - (n - 1), slope = 1.;
              else if (i == n - 1)
                value = n - x, slope = -1.;
            }
          else if (std::abs(s) <= 0.5)
            value = 0.75 - s * s, slope = -2. * s;
          else if (std::abs(s) < 1.5)
            {
              const double r = 1.5 - std::abs(s);
              value          = 0.5 * r * r;
              slope          = s > 0. ? -r : r;
            }
          w.value[k] = value;
          w.slope[k] = slope;
        }
      return w;
    }

  } // namespace



  template <int dim>
  std::array<LatticeWeights, dim>
  BsplineFunctions<dim>::weights(const Point<dim> &           x,
                                 const std::array<int, dim> & corner,
                                 const ArrayView<const double> &) const
  {
    std::array<LatticeWeights, dim> w;
    for (unsigned int d = 0; d < dim; ++d)
      w[d] = bspline_weights(x[d], corner[d], this->node_lattice.n_cells(d));
    return w;
  }



  template <int dim>
  void
  BsplineFunctions<dim>::cell_integrals(const unsigned int active_cell_index,
                                        Support<dim> &     integrals) const
  {
    // B-splines are quadratic on each half cell: two Gauss points on each
    // half, per direction, are exact.
    const typename NodeLattice<dim>::Cell &cell =
      this->node_lattice.cell(active_cell_index);
    std::array<std::array<double, 4>, dim> per_direction;
    const double                           offset = 0.25 / std::sqrt(3.);
    for (unsigned int d = 0; d < dim; ++d)
      {
        per_direction[d].fill(0.);
        for (const double x : {0.25 - offset, 0.25 + offset,
                               0.75 - offset, 0.75 + offset})
          {
            const LatticeWeights w = bspline_weights(cell.corner[d] + x,
                                                cell.corner[d],
                                                this->node_lattice.n_cells(d));
            for (unsigned int k = 0; k < 4; ++k)
              per_direction[d][k] += 0.25 * w.value[k] /
                                     this->node_lattice.inverse_h()[d];
          }
      }
    integrals.resize(0);
    for (unsigned int patch_index = 0;
         patch_index < NodeLattice<dim>::n_patch_nodes;
         ++patch_index)
      {
        double value = 1.;
        for (unsigned int d = 0, rest = patch_index; d < dim; ++d, rest /= 4)
          value *= per_direction[d][rest % 4];
        if (value == 0.)
          continue;
        const unsigned int j = integrals.n_nodes;
        integrals.resize(j + 1);
        integrals.nodes[j] = cell.nodes[patch_index];
        integrals.N[j]     = value;
      }
  }



  template class BsplineFunctions<2>;
  template class BsplineFunctions<3>;
} // namespace mpm
