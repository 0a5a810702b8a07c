#include <mpm/materials/hencky.h>
#include <mpm/materials/principal_axes.h>

#include <cmath>

namespace mpm
{
  Hencky::Hencky(const ParameterHandler &prm,
                 const std::string &     name,
                 const std::string &     section_path)
    : Material(prm, name, section_path)
  {}



  void
  Hencky::update_stress(const StepKinematics &kinematics,
                        SymmetricTensor<2, 3> &stress,
                        const ArrayView<double> &) const
  {
    const Tensor<2, 3> &        F = kinematics.F_new;
    const SymmetricTensor<2, 3> b = symmetrize(Tensor<2, 3>(F * transpose(F)));
    SymmetricTensor<2, 3>       log_strain;
    for (const auto &[value, direction] :
         principal_axes(b, SymmetricTensorEigenvectorMethod::ql_implicit_shifts))
      log_strain += 0.5 * std::log(value) *
                    symmetrize(outer_product(direction, direction));
    const SymmetricTensor<2, 3> tau =
      lambda * trace(log_strain) * unit_symmetric_tensor<3>() +
      2. * mu * log_strain;
    stress = tau / determinant(F);
  }



  SymmetricTensor<4, 3>
  Hencky::spatial_tangent(const StepKinematics &         kinematics,
                          const SymmetricTensor<2, 3> &  old_stress,
                          const ArrayView<const double> &old_internal_variables)
    const
  {
    return numerical_spatial_tangent(kinematics,
                                     old_stress,
                                     old_internal_variables);
  }



  MPM_REGISTER_MATERIAL(Hencky,
                        "Hencky",
                        "hyperelastic, Kirchhoff stress linear in the "
                        "logarithmic strain.",
                        nullptr)
} // namespace mpm
