#ifndef mpm_materials_linear_elastic_h
#define mpm_materials_linear_elastic_h

#include <mpm/materials/material.h>

namespace mpm
{
  /**
   * Hypoelastic isotropic law integrated with the Jaumann rate, as in [W]:
   * sigma += dt (lambda tr(D) I + 2 mu D + W sigma - sigma W),
   * with D and W the symmetric and skew parts of the velocity gradient.
   * Its tangent is the isotropic elastic stiffness, which is the consistent
   * one only to first order in the stress over the modulus: the law has no
   * stored energy, and implicit schemes converge with it linearly.
   */
  class LinearElastic : public Material
  {
  public:
    LinearElastic(const ParameterHandler &prm,
                  const std::string &     name,
                  const std::string &     section_path);

    void
    update_stress(const StepKinematics &   kinematics,
                  SymmetricTensor<2, 3> &  stress,
                  const ArrayView<double> &internal_variables) const override;

    SymmetricTensor<4, 3>
    spatial_tangent(const StepKinematics &         kinematics,
                    const SymmetricTensor<2, 3> &  stress,
                    const ArrayView<const double> &internal_variables)
      const override;
  };
} // namespace mpm

#endif
