#include <mpm/materials/linear_elastic.h>

namespace mpm
{
  LinearElastic::LinearElastic(const ParameterHandler &prm,
                               const std::string &     name,
                               const std::string &     section_path)
    : Material(prm, name, section_path)
  {}



  void
  LinearElastic::update_stress(const StepKinematics &kinematics,
                               SymmetricTensor<2, 3> &stress,
                               const ArrayView<double> &) const
  {
    const Tensor<2, 3> &        L = kinematics.velocity_gradient;
    const SymmetricTensor<2, 3> D = symmetrize(L);
    const Tensor<2, 3>          W = 0.5 * (L - transpose(L));
    const Tensor<2, 3>          sigma(stress);
    // W sigma - sigma W is symmetric for symmetric sigma and skew W.
    const SymmetricTensor<2, 3> rotation =
      symmetrize(Tensor<2, 3>(W * sigma - sigma * W));
    stress += kinematics.dt *
              (lambda * trace(D) * unit_symmetric_tensor<3>() + 2. * mu * D +
               rotation);
  }



  SymmetricTensor<4, 3>
  LinearElastic::spatial_tangent(const StepKinematics &,
                                 const SymmetricTensor<2, 3> &,
                                 const ArrayView<const double> &) const
  {
    const SymmetricTensor<2, 3> I = unit_symmetric_tensor<3>();
    return lambda * outer_product(I, I) + 2. * mu * identity_tensor<3>();
  }
} // namespace mpm
