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
} // namespace mpm
