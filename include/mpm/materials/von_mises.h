#ifndef mpm_materials_von_mises_h
#define mpm_materials_von_mises_h

#include <mpm/materials/hencky_plasticity.h>

namespace mpm
{
  /**
   * von Mises (J2) plasticity with linear isotropic hardening, Hencky
   * elasticity at finite strain (HenckyPlasticity): f = q - (sigma_y + H
   * eps_p), q = sqrt(3/2) |dev tau|, by the radial return, whose
   * algorithmic tangent is D_alg = K 1 (x) 1 + 2 mu (1 - 3 mu dgamma / q)
   * I_dev + 6 mu^2 (dgamma / q - 1 / (3 mu + H)) n (x) n, n = dev tau /
   * |dev tau| (de Souza Neto et al., Box 7.2). H = 0 is perfectly plastic.
   */
  class VonMises : public HenckyPlasticity
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    VonMises(ParameterHandler & prm,
             const std::string &name,
             const std::string &section_path);

    Return
    return_to_yield_surface(const Tensor<1, 3> &trial_tau,
                            double              plastic_strain,
                            bool                with_tangent) const override;

    double
    yield_function(const Tensor<1, 3> &tau,
                   double              plastic_strain) const override;

  private:
    double yield_stress;
    double hardening_modulus;
  };
} // namespace mpm

#endif
