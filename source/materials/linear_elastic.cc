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
    stress += kinematics.dt *
              (lambda * trace(D) * unit_symmetric_tensor<3>() + 2. * mu * D +
               jaumann_rotation(L, stress));
  }



  double
  LinearElastic::initialize_stress(const SymmetricTensor<2, 3> &stress,
                                   const ArrayView<double> &,
                                   const std::string &) const
  {
    return elastic_energy_density(stress);
  }



  SymmetricTensor<2, 3>
  LinearElastic::jaumann_rotation(const Tensor<2, 3> &         L,
                                  const SymmetricTensor<2, 3> &stress)
  {
    const Tensor<2, 3> W = 0.5 * (L - transpose(L));
    const Tensor<2, 3> sigma(stress);
    // W sigma - sigma W is symmetric for symmetric sigma and skew W.
    return symmetrize(Tensor<2, 3>(W * sigma - sigma * W));
  }



  SymmetricTensor<4, 3>
  LinearElastic::spatial_tangent(
    const StepKinematics &         kinematics,
    const SymmetricTensor<2, 3> &  old_stress,
    const ArrayView<const double> &old_internal_variables) const
  {
    // The Jaumann update depends on the old stress and the spin; its
    // consistent tangent by differences of the update itself.
    return numerical_spatial_tangent(kinematics,
                                     old_stress,
                                     old_internal_variables);
  }



  MPM_REGISTER_MATERIAL(LinearElastic,
                        "linear elastic",
                        "hypoelastic, integrated with the Jaumann stress "
                        "rate as in Wieckowski (2004).",
                        nullptr)
} // namespace mpm
