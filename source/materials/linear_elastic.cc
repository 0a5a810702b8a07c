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
    // For symmetric sigma and skew W, sigma W = -(W sigma)^T, so
    // W sigma - sigma W = A + A^T with A = W sigma, and W has three
    // entries: written out, a third of the products of two full 3 x 3
    // ones, with the same values (the terms dropped are W_ii = 0; an
    // exact zero may come out as -0).
    const double w01 = 0.5 * (L[0][1] - L[1][0]);
    const double w02 = 0.5 * (L[0][2] - L[2][0]);
    const double w12 = 0.5 * (L[1][2] - L[2][1]);
    const double s00 = stress[0][0], s11 = stress[1][1], s22 = stress[2][2];
    const double s01 = stress[0][1], s02 = stress[0][2], s12 = stress[1][2];
    const double A00 = w01 * s01 + w02 * s02;
    const double A11 = -w01 * s01 + w12 * s12;
    const double A22 = -w02 * s02 - w12 * s12;
    const double A01 = w01 * s11 + w02 * s12;
    const double A10 = -w01 * s00 + w12 * s02;
    const double A02 = w01 * s12 + w02 * s22;
    const double A20 = -w02 * s00 - w12 * s01;
    const double A12 = -w01 * s02 + w12 * s22;
    const double A21 = -w02 * s01 - w12 * s11;
    SymmetricTensor<2, 3> rotation;
    rotation[0][0] = A00 + A00;
    rotation[1][1] = A11 + A11;
    rotation[2][2] = A22 + A22;
    rotation[0][1] = A01 + A10;
    rotation[0][2] = A02 + A20;
    rotation[1][2] = A12 + A21;
    return rotation;
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
