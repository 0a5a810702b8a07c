#ifndef mpm_assembly_point_assembly_h
#define mpm_assembly_point_assembly_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>

#include <mpm/basis/support.h>

#include <array>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The updated-Lagrangian contribution of one material point to the
   * internal force and the tangent, [I] eqs. (30)-(34): the one assembly that
   * implicit and quasi-static MPM (and the meshfree method) share. It sees a
   * point only through its Support at the start of the step, so it does not
   * know which basis made it.
   *
   * Local degrees of freedom are numbered node-major: (node i, component a)
   * is i * dim + a.
   *
   * The explicit schemes call the same internal force with dF = I (no
   * `deformation_increment`): their supports are evaluated at the current
   * positions.
   */
  template <int dim>
  class PointAssembly
  {
  public:
    /**
     * Storage that internal_force() reuses from point to point, so that a
     * loop over points allocates only at its first point.
     */
    struct Scratch
    {
      std::vector<Tensor<1, dim>>                    g;
      std::vector<std::array<double, dim * dim * dim>> c_g;
      std::vector<double>                            force;
    };

    /**
     * Deformation gradient of the step, dF = I + sum_i du_i (x) grad N_i,
     * with the gradients at the start of the step and du_i the displacement
     * increments of the support's nodes.
     */
    static Tensor<2, dim>
    deformation_increment(const Support<dim> &               support,
                          const std::vector<Tensor<1, dim>> &displacement);

    /**
     * Internal force r_(i a) = v sigma_(a c) g_i[c] with g_i = dF^-T grad N_i
     * the gradient in the current configuration (grad N_i itself if
     * `deformation_increment` is nullptr) and v the current volume;
     * and, if `tangent` is given, the tangent
     * K_(i a)(k b) = v (c_(a c b d) g_i[c] g_k[d] + g_i . sigma . g_k
     * delta_ab), material plus geometric stiffness. In 2D the in-plane
     * blocks of the 3x3 stress and tangent are used (plane strain).
     *
     * A point of an axisymmetric scene gives its current radius r
     * (`hoop_radius` > 0; 0 otherwise). Its zz is then the hoop direction,
     * whose displacement gradient is u_r / r: a radial displacement of node
     * i adds h_i = N_i / r to it. The force gains v sigma_tt h_i ([W] eq.
     * 5), and the tangent the terms of that gradient entry: material v (h_i
     * c_(tt b q) g_k[q] + c_(a p tt) g_i[p] h_k + h_i c_(tttt) h_k) and
     * geometric v sigma_tt h_i h_k.
     *
     * The force is left in `scratch.force`.
     */
    static void
    internal_force(const Support<dim> &          support,
                   const Tensor<2, dim> *        deformation_increment,
                   const double                  current_volume,
                   const SymmetricTensor<2, 3> & stress,
                   const SymmetricTensor<4, 3> *spatial_tangent,
                   FullMatrix<double> *          tangent,
                   Scratch &                     scratch,
                   const double                  hoop_radius = 0.)
    {
      // Gradients in the current configuration: grad_x N = dF^-T grad_xn N.
      const Tensor<1, dim> *g = support.grad_N.data();
      if (deformation_increment != nullptr)
        {
          const Tensor<2, dim> inverse_transpose =
            transpose(invert(*deformation_increment));
          scratch.g.resize(support.n_nodes);
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            scratch.g[i] = inverse_transpose * support.grad_N[i];
          g = scratch.g.data();
        }

      Tensor<2, dim> sigma;
      for (unsigned int a = 0; a < dim; ++a)
        for (unsigned int b = 0; b < dim; ++b)
          sigma[a][b] = stress[a][b];

      scratch.force.resize(support.n_nodes * dim);
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          const Tensor<1, dim> force = current_volume * (sigma * g[i]);
          for (unsigned int a = 0; a < dim; ++a)
            scratch.force[i * dim + a] = force[a];
        }

      // The tangent's geometric part reads the in-plane force: the hoop
      // force joins it after.
      if (tangent != nullptr)
        add_tangent(support,
                    g,
                    current_volume,
                    *spatial_tangent,
                    stress[2][2],
                    hoop_radius,
                    *tangent,
                    scratch);
      if (hoop_radius > 0.)
        for (unsigned int i = 0; i < support.n_nodes; ++i)
          scratch.force[i * dim] +=
            current_volume * stress[2][2] * support.N[i] / hoop_radius;
    }

  private:
    /**
     * The tangent of internal_force(), from the current gradients `g` and
     * the force already in `scratch`.
     */
    static void
    add_tangent(const Support<dim> &         support,
                const Tensor<1, dim> *       g,
                const double                 current_volume,
                const SymmetricTensor<4, 3> &c,
                const double                 hoop_stress,
                const double                 hoop_radius,
                FullMatrix<double> &         tangent,
                Scratch &                    scratch);
  };
} // namespace mpm

#endif
