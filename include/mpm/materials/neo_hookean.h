#ifndef mpm_materials_neo_hookean_h
#define mpm_materials_neo_hookean_h

#include <mpm/materials/material.h>

namespace mpm
{
  /**
   * Compressible neo-Hookean law:
   * sigma = (mu (b - I) + lambda ln(J) I) / J, b = F F^T, J = det F.
   * In uniaxial strain with nu = 0 it gives sigma = E sinh(eps_L), the
   * closed form the oedometer benchmark checks.
   */
  class NeoHookean : public Material
  {
  public:
    NeoHookean(const ParameterHandler &prm,
               const std::string &     name,
               const std::string &     section_path);

    void
    update_stress(const StepKinematics &   kinematics,
                  SymmetricTensor<2, 3> &  stress,
                  const ArrayView<double> &internal_variables) const override;

    SymmetricTensor<4, 3>
    spatial_tangent(const StepKinematics &         kinematics,
                    const SymmetricTensor<2, 3> &  old_stress,
                    const ArrayView<const double> &old_internal_variables)
      const override;
  };
} // namespace mpm

#endif
