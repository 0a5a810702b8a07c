#include <mpm/basis/linear_functions.h>

#include <cmath>

namespace mpm
{
  template <int dim>
  void
  LinearFunctions<dim>::cell_integrals(const unsigned int active_cell_index,
                                 Support<dim> &     integrals) const
  {
    const double        offset = 0.5 / std::sqrt(3.);
    const CellGeometry &cell   = grid.cell_geometry(active_cell_index);
    integrals.resize(n_vertices);
    std::array<double, n_vertices>         values;
    std::array<Tensor<1, dim>, n_vertices> grad_ref;
    for (unsigned int v = 0; v < n_vertices; ++v)
      {
        integrals.nodes[v] = cell.nodes[v];
        integrals.N[v]     = 0.;
      }
    for (unsigned int q = 0; q < n_vertices; ++q)
      {
        Point<dim> xi;
        for (unsigned int d = 0; d < dim; ++d)
          xi[d] = (q & (1u << d)) ? 0.5 + offset : 0.5 - offset;
        reference_values(xi, values, grad_ref);
        const double weight =
          determinant(jacobian(cell, grad_ref)) / n_vertices;
        for (unsigned int v = 0; v < n_vertices; ++v)
          integrals.N[v] += weight * values[v];
      }
    if (cell.n_hanging > 0)
      condense_hanging_vertices(cell, integrals);
  }



  template <int dim>
  void
  LinearFunctions<dim>::condense_hanging_vertices(const CellGeometry &cell,
                                            Support<dim> &      support) const
  {
    std::array<double, n_vertices>         value;
    std::array<Tensor<1, dim>, n_vertices> gradient;
    std::array<bool, n_vertices>           hangs = {};
    const auto hanging = grid.hanging_vertices(cell);
    for (const auto &entry : hanging)
      hangs[entry.vertex] = true;
    unsigned int n = 0;
    for (unsigned int v = 0; v < n_vertices; ++v)
      {
        value[v]    = support.N[v];
        gradient[v] = support.grad_N[v];
        if (!hangs[v])
          {
            support.nodes[n]  = support.nodes[v];
            support.N[n]      = value[v];
            support.grad_N[n] = gradient[v];
            ++n;
          }
      }
    for (const auto &entry : hanging)
      {
        unsigned int i = 0;
        while (i < n && support.nodes[i] != entry.master)
          ++i;
        if (i == n)
          {
            support.resize(++n);
            support.nodes[i]  = entry.master;
            support.N[i]      = 0.;
            support.grad_N[i] = Tensor<1, dim>();
          }
        support.N[i] += entry.weight * value[entry.vertex];
        support.grad_N[i] += entry.weight * gradient[entry.vertex];
      }
    support.n_nodes = n;
  }



  template class LinearFunctions<2>;
  template class LinearFunctions<3>;
} // namespace mpm
