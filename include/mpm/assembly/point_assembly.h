#ifndef mpm_assembly_point_assembly_h
#define mpm_assembly_point_assembly_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

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
   */
  template <int dim>
  class PointAssembly
  {
  public:
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
     * the gradient in the current configuration and v the current volume;
     * and, if `tangent` is given, the tangent
     * K_(i a)(k b) = v (c_(a c b d) g_i[c] g_k[d] + g_i . sigma . g_k
     * delta_ab), material plus geometric stiffness. In 2D the in-plane
     * blocks of the 3x3 stress and tangent are used (plane strain).
     */
    static void
    internal_force(const Support<dim> &          support,
                   const Tensor<2, dim> &        deformation_increment,
                   const double                  current_volume,
                   const SymmetricTensor<2, 3> & stress,
                   const SymmetricTensor<4, 3> *spatial_tangent,
                   Vector<double> &              force,
                   FullMatrix<double> *          tangent);
  };
} // namespace mpm

#endif
