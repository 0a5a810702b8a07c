#ifndef mpm_materials_principal_axes_h
#define mpm_materials_principal_axes_h

#include <deal.II/base/symmetric_tensor.h>

#include <array>
#include <cmath>
#include <utility>

namespace mpm
{
  using namespace dealii;

  /**
   * The eigenvalues and unit eigenvectors of a symmetric tensor, largest
   * first, as deal.II's eigenvectors() gives them.
   *
   * In 2D scenes (plane strain, plane stress, axisymmetry) the tensors of
   * the finite-strain laws have t_xz = t_yz = 0 exactly, so z is an axis
   * and the in-plane pair has a closed form; that is several times cheaper
   * than deal.II's iterative Jacobi rotations, which were the largest
   * single cost of an explicit Mohr-Coulomb step. Other tensors go to
   * deal.II's `general` method.
   */
  inline std::array<std::pair<double, Tensor<1, 3>>, 3>
  principal_axes(const SymmetricTensor<2, 3> &     t,
                 const SymmetricTensorEigenvectorMethod general =
                   SymmetricTensorEigenvectorMethod::jacobi)
  {
    if (t[0][2] != 0. || t[1][2] != 0.)
      return eigenvectors(t, general);

    const double a = t[0][0], c = t[0][1], d = t[1][1];
    const double mean   = 0.5 * (a + d);
    const double radius = std::sqrt(0.25 * (a - d) * (a - d) + c * c);
    // The smaller one from the determinant where the difference of the
    // two would cancel (the stretches of b are positive).
    const double larger = mean + radius;
    // Within round-off of each other the determinant form may come out an
    // ulp above the larger one.
    const double smaller =
      std::min(larger,
               (mean > 0. && larger > 0.) ? (a * d - c * c) / larger :
                                            mean - radius);
    Tensor<1, 3> first, second;
    if (radius == 0.)
      {
        first[0]  = 1.;
        second[1] = 1.;
      }
    else
      {
        // Each column of t - smaller I is a multiple of the first axis:
        // take the longer one.
        const double u0 = a - smaller, u1 = d - smaller;
        if (u0 * u0 >= u1 * u1)
          {
            first[0] = u0;
            first[1] = c;
          }
        else
          {
            first[0] = c;
            first[1] = u1;
          }
        first /= first.norm();
        second[0] = -first[1];
        second[1] = first[0];
      }
    Tensor<1, 3> z;
    z[2] = 1.;
    std::array<std::pair<double, Tensor<1, 3>>, 3> axes = {
      {{larger, first}, {smaller, second}, {t[2][2], z}}};
    // Largest first.
    if (axes[2].first > axes[1].first)
      std::swap(axes[2], axes[1]);
    if (axes[1].first > axes[0].first)
      std::swap(axes[1], axes[0]);
    return axes;
  }
} // namespace mpm

#endif
