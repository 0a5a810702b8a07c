#ifndef mpm_materials_hencky_h
#define mpm_materials_hencky_h

#include <mpm/materials/material.h>

namespace mpm
{
  /**
   * Hencky hyperelasticity: the Kirchhoff stress is linear in the
   * logarithmic strain, tau = lambda tr(eps) I + 2 mu eps with
   * eps = 1/2 ln(b); sigma = tau / J. The large-strain version of linear
   * elasticity that implicit schemes need (it has a stored energy). In
   * uniaxial strain with nu = 0: sigma = E eps_L / exp(eps_L).
   */
  class Hencky : public Material
  {
  public:
    Hencky(const ParameterHandler &prm,
           const std::string &     name,
           const std::string &     section_path);

    void
    update_stress(const StepKinematics &   kinematics,
                  SymmetricTensor<2, 3> &  stress,
                  const ArrayView<double> &internal_variables) const override;

    /** By central differences of the stress (numerical_spatial_tangent). */
    SymmetricTensor<4, 3>
    spatial_tangent(const StepKinematics &         kinematics,
                    const SymmetricTensor<2, 3> &  old_stress,
                    const ArrayView<const double> &old_internal_variables)
      const override;
  };
} // namespace mpm

#endif
