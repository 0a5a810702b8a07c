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
  PointAssembly<dim>::internal_force(
    const Support<dim> &          support,
    const Tensor<2, dim> &        deformation_increment,
    const double                  current_volume,
    const SymmetricTensor<2, 3> & stress,
    const SymmetricTensor<4, 3> *spatial_tangent,
    Vector<double> &              force,
    FullMatrix<double> *          tangent)
  {
    const unsigned int n_dofs = support.n_nodes * dim;
    force.reinit(n_dofs);

    // Gradients in the current configuration: grad_x N = dF^-T grad_xn N.
    const Tensor<2, dim> inverse_transpose =
      transpose(invert(deformation_increment));
    std::vector<Tensor<1, dim>> g(support.n_nodes);
    for (unsigned int i = 0; i < support.n_nodes; ++i)
      g[i] = inverse_transpose * support.grad_N[i];

    Tensor<2, dim> sigma;
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int b = 0; b < dim; ++b)
        sigma[a][b] = stress[a][b];

    // v sigma g_i: node i's internal force, and the geometric stiffness's
    // factor below.
    std::vector<Tensor<1, dim>> sigma_g(support.n_nodes);
    for (unsigned int i = 0; i < support.n_nodes; ++i)
      {
        sigma_g[i] = current_volume * (sigma * g[i]);
        for (unsigned int a = 0; a < dim; ++a)
          force(i * dim + a) = sigma_g[i][a];
      }

    if (tangent == nullptr)
      return;
    tangent->reinit(n_dofs, n_dofs);
    // c[a][p][b][q] g_k[q], once per node k: the pair loop below is then
    // dim^3 products on plain arrays, not dim^4 SymmetricTensor lookups
    // (the meshfree supports make it the innermost loop of a GMM step).
    const SymmetricTensor<4, 3> &c = *spatial_tangent;
    double c_plain[dim][dim][dim][dim];
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int p = 0; p < dim; ++p)
        for (unsigned int b = 0; b < dim; ++b)
          for (unsigned int q = 0; q < dim; ++q)
            c_plain[a][p][b][q] = current_volume * c[a][p][b][q];
    std::vector<std::array<double, dim * dim * dim>> c_g(support.n_nodes);
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
          const double geometric = g[i] * sigma_g[k];
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int b = 0; b < dim; ++b)
              {
                double material = 0.;
                for (unsigned int p = 0; p < dim; ++p)
                  material += g[i][p] * c_g[k][(a * dim + p) * dim + b];
                (*tangent)(i * dim + a, k * dim + b) =
                  material + (a == b ? geometric : 0.);
              }
        }
  }



  template class PointAssembly<2>;
  template class PointAssembly<3>;
} // namespace mpm
