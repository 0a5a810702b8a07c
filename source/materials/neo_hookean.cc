#include <mpm/materials/neo_hookean.h>

#include <cmath>

namespace mpm
{
  NeoHookean::NeoHookean(const ParameterHandler &prm,
                         const std::string &     name,
                         const std::string &     section_path)
    : Material(prm, name, section_path)
  {}



  void
  NeoHookean::update_stress(const StepKinematics &kinematics,
                            SymmetricTensor<2, 3> &stress,
                            const ArrayView<double> &) const
  {
    const Tensor<2, 3> &        F = kinematics.F_new;
    const double                J = determinant(F);
    const SymmetricTensor<2, 3> b = symmetrize(Tensor<2, 3>(F * transpose(F)));
    const SymmetricTensor<2, 3> I = unit_symmetric_tensor<3>();
    stress = (mu * (b - I) + lambda * std::log(J) * I) / J;
  }



  SymmetricTensor<4, 3>
  NeoHookean::spatial_tangent(const StepKinematics &kinematics,
                              const SymmetricTensor<2, 3> &,
                              const ArrayView<const double> &) const
  {
    // tau = mu (b - I) + lambda ln(J) I gives, for the Truesdell rate of tau,
    // c_tau = lambda I (x) I + 2 (mu - lambda ln J) II; c = c_tau / J.
    const double                J = determinant(kinematics.F_new);
    const SymmetricTensor<2, 3> I = unit_symmetric_tensor<3>();
    return (lambda * outer_product(I, I) +
            2. * (mu - lambda * std::log(J)) * identity_tensor<3>()) /
           J;
  }



  MPM_REGISTER_MATERIAL(NeoHookean,
                        "neo-Hookean",
                        "compressible hyperelastic, sigma = (mu (b - I) + "
                        "lambda ln(J) I)/J.",
                        nullptr)
} // namespace mpm
