#ifndef mpm_materials_mohr_coulomb_h
#define mpm_materials_mohr_coulomb_h

#include <mpm/materials/hencky_plasticity.h>

namespace mpm
{
  /**
   * Mohr-Coulomb, elastic-perfectly plastic, with Hencky elasticity at
   * finite strain (HenckyPlasticity). With the principal Kirchhoff stresses
   * ordered tau_1 >= tau_2 >= tau_3 (tension positive), the yield function
   * is f = k tau_1 - tau_3 - 2 c sqrt(k), k = (1 + sin phi) / (1 - sin
   * phi), and the plastic potential g = m tau_1 - tau_3 with m from the
   * dilatancy angle psi (non-associated for psi < phi). The return in
   * principal stress space follows Clausen, Damkilde and Andersen (2006):
   * to the plane, to one of the two edges (tau_1 = tau_2 or tau_2 =
   * tau_3) with two multipliers, or to the apex tau = c cot(phi); each is
   * exact for the linear surfaces, and each has its algorithmic tangent
   * (zero at the apex). phi = 0 is Tresca. The equivalent plastic strain
   * grows by sqrt(2/3 |d eps_p|^2) of the principal plastic strain step.
   */
  class MohrCoulomb : public HenckyPlasticity
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    MohrCoulomb(ParameterHandler & prm,
                const std::string &name,
                const std::string &section_path);

    Return
    return_to_yield_surface(const Tensor<1, 3> &trial_tau,
                            double              plastic_strain) const override;

    double
    yield_function(const Tensor<1, 3> &tau,
                   double              plastic_strain) const override;

  private:
    double cohesion;
    double k;
    double m;
  };
} // namespace mpm

#endif
