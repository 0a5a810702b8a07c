#include <mpm/basis/lattice_functions.h>

namespace mpm
{
  template <int dim>
  void
  LatticeFunctions<dim>::evaluate(const unsigned int             active_cell_index,
                                  const Point<dim> &             reference_point,
                                  const ArrayView<const double> &p,
                                  Support<dim> &                 support) const
  {
    const typename NodeLattice<dim>::Cell &cell =
      node_lattice.cell(active_cell_index);
    Point<dim> x;
    for (unsigned int d = 0; d < dim; ++d)
      x[d] = cell.corner[d] + reference_point[d];
    const std::array<Weights1D, dim> w = weights(x, cell.corner, p);

    // Per direction, the nodes (k) that carry the point.
    std::array<std::array<unsigned int, 3>, dim> reached;
    std::array<unsigned int, dim>                n_reached;
    for (unsigned int d = 0; d < dim; ++d)
      {
        n_reached[d] = 0;
        for (unsigned int k = 0; k < 4; ++k)
          if (w[d].value[k] != 0. || w[d].slope[k] != 0.)
            {
              Assert(n_reached[d] < 3, ExcInternalError());
              reached[d][n_reached[d]++] = k;
            }
      }

    unsigned int n = 1;
    for (unsigned int d = 0; d < dim; ++d)
      n *= n_reached[d];
    support.resize(n);
    const Tensor<1, dim> &inverse_h = node_lattice.inverse_h();
    unsigned int          kept      = 0;
    for (unsigned int j = 0; j < n; ++j)
      {
        unsigned int patch_index = 0, stride = 1, rest = j;
        std::array<unsigned int, dim> k;
        for (unsigned int d = 0; d < dim; ++d)
          {
            k[d] = reached[d][rest % n_reached[d]];
            rest /= n_reached[d];
            patch_index += k[d] * stride;
            stride *= NodeLattice<dim>::patch_width;
          }
        double value = 1.;
        for (unsigned int d = 0; d < dim; ++d)
          value *= w[d].value[k[d]];
        Tensor<1, dim> gradient;
        for (unsigned int g = 0; g < dim; ++g)
          {
            double component = w[g].slope[k[g]] * inverse_h[g];
            for (unsigned int d = 0; d < dim; ++d)
              if (d != g)
                component *= w[d].value[k[d]];
            gradient[g] = component;
          }
        // A node whose value and slope vanish in different directions
        // carries nothing.
        if (value == 0. && gradient.norm_square() == 0.)
          continue;
        support.nodes[kept] = cell.nodes[patch_index];
        Assert(support.nodes[kept] != NodeLattice<dim>::no_node,
               ExcInternalError());
        support.N[kept]      = value;
        support.grad_N[kept] = gradient;
        ++kept;
      }
    support.n_nodes = kept;
  }



  template class LatticeFunctions<2>;
  template class LatticeFunctions<3>;
} // namespace mpm
