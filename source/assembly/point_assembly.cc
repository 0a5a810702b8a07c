#include <mpm/assembly/point_assembly.h>

namespace mpm
{
  template <int dim>
  Tensor<2, dim>
  PointAssembly<dim>::deformation_increment(
    const Support<dim> &               support,
    const std::vector<Tensor<1, dim>> &displacement)
  {
    Tensor<2, dim> dF = unit_symmetric_tensor<dim>();
    for (unsigned int i = 0; i < support.n_nodes; ++i)
      dF += outer_product(displacement[i], support.grad_N[i]);
    return dF;
  }



  template <int dim>
  void
  PointAssembly<dim>::add_tangent(const Support<dim> &         support,
                                  const Tensor<1, dim> *       g,
                                  const double                 current_volume,
                                  const SymmetricTensor<4, 3> &c,
                                  const double                 hoop_stress,
                                  const double                 hoop_radius,
                                  FullMatrix<double> &         tangent,
                                  Scratch &                    scratch)
  {
    const unsigned int n_dofs = support.n_nodes * dim;
    tangent.reinit(n_dofs, n_dofs);
    // c[a][p][b][q] g_k[q], once per node k: the pair loop below is then
    // dim^3 products on plain arrays, not dim^4 SymmetricTensor lookups
    // (the meshfree supports make it the innermost loop of a GMM step).
    double c_plain[dim][dim][dim][dim];
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int p = 0; p < dim; ++p)
        for (unsigned int b = 0; b < dim; ++b)
          for (unsigned int q = 0; q < dim; ++q)
            c_plain[a][p][b][q] = current_volume * c[a][p][b][q];
    std::vector<std::array<double, dim * dim * dim>> &c_g = scratch.c_g;
    c_g.resize(support.n_nodes);
    for (unsigned int k = 0; k < support.n_nodes; ++k)
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int p = 0; p < dim; ++p)
          for (unsigned int b = 0; b < dim; ++b)
            {
              double sum = 0.;
              for (unsigned int q = 0; q < dim; ++q)
                sum += c_plain[a][p][b][q] * g[k][q];
              c_g[k][(a * dim + p) * dim + b] = sum;
            }
    for (unsigned int i = 0; i < support.n_nodes; ++i)
      for (unsigned int k = 0; k < support.n_nodes; ++k)
        {
          // g_i . (v sigma g_k), with v sigma g_k the force of node k.
          double geometric = 0.;
          for (unsigned int a = 0; a < dim; ++a)
            geometric += g[i][a] * scratch.force[k * dim + a];
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int b = 0; b < dim; ++b)
              {
                double material = 0.;
                for (unsigned int p = 0; p < dim; ++p)
                  material += g[i][p] * c_g[k][(a * dim + p) * dim + b];
                tangent(i * dim + a, k * dim + b) =
                  material + (a == b ? geometric : 0.);
              }
        }
    if (hoop_radius > 0.)
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          const double h_i = support.N[i] / hoop_radius;
          for (unsigned int k = 0; k < support.n_nodes; ++k)
            {
              const double h_k = support.N[k] / hoop_radius;
              for (unsigned int b = 0; b < dim; ++b)
                {
                  // The hoop row of node i against component b of node k,
                  // and the in-plane rows of node i against the hoop
                  // column of node k.
                  double row = 0., column = 0.;
                  for (unsigned int q = 0; q < dim; ++q)
                    {
                      row += c[2][2][b][q] * g[k][q];
                      column += c[b][q][2][2] * g[i][q];
                    }
                  tangent(i * dim, k * dim + b) +=
                    current_volume * h_i * row;
                  tangent(i * dim + b, k * dim) +=
                    current_volume * column * h_k;
                }
              tangent(i * dim, k * dim) +=
                current_volume * h_i * h_k * (c[2][2][2][2] + hoop_stress);
            }
        }
  }



  template class PointAssembly<2>;
  template class PointAssembly<3>;
} // namespace mpm
