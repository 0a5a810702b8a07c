#ifndef mpm_materials_linear_elastic_h
#define mpm_materials_linear_elastic_h

#include <mpm/materials/material.h>

namespace mpm
{
  /**
   * Hypoelastic isotropic law integrated with the Jaumann rate, as in [W]:
   * sigma += dt (lambda tr(D) I + 2 mu D + W sigma - sigma W),
   * with D and W the symmetric and skew parts of the velocity gradient.
   * Its tangent is the derivative of this update by central differences
   * (numerical_spatial_tangent): consistent for stretches; a rotation of
   * the step is only objective to first order in dt L, as for any Jaumann
   * integration.
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
                    const SymmetricTensor<2, 3> &  old_stress,
                    const ArrayView<const double> &old_internal_variables)
      const override;

    /** The stress itself is the state: nothing else to set. */
    double
    initialize_stress(const SymmetricTensor<2, 3> &stress,
                      const ArrayView<double> &    internal_variables,
                      const std::string &          who) const override;

    /**
     * The rotation part of the Jaumann rate, W sigma - sigma W, with W the
     * spin of the velocity gradient L: traceless, so it turns the deviator
     * only.
     */
    static SymmetricTensor<2, 3>
    jaumann_rotation(const Tensor<2, 3> &         L,
                     const SymmetricTensor<2, 3> &stress);
  };
} // namespace mpm

#endif
