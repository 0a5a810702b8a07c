#ifndef mpm_materials_drucker_prager_viscoplastic_h
#define mpm_materials_drucker_prager_viscoplastic_h

#include <mpm/materials/linear_elastic.h>

namespace mpm
{
  /**
   * The elastic-viscoplastic Drucker-Prager law of Wieckowski (2004),
   * eqs. (15)-(23), for cohesionless granular material. Hypoelastic with
   * the Jaumann rate (the elastic predictor is LinearElastic's update);
   * the viscoplastic flow is Perzyna's, isochoric and non-associated:
   * d_vp = gamma <Phi> dq/dsigma, Phi = ((q - m p) / (m p))^N, with
   * p = -tr(sigma)/3, q = sqrt(3/2 s:s) and m = 18 sin(phi) / (9 -
   * sin^2(phi)) as in [W]. Backward Euler gives the deviator
   * s = s_trial q / q_trial, q = q_trial - 3 G de, and the scalar equation
   * (22) de = gamma dt ((q_trial - m p - 3 G de) / (m p))^N: closed form for
   * N = 1, a bracketed Newton iteration otherwise. The pressure is
   * elastic. Cohesionless: a point in tension (p <= 0) carries no stress.
   * Internal variable: the accumulated viscoplastic strain de,
   * `plastic_strain`.
   */
  class DruckerPragerViscoplastic : public LinearElastic
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    DruckerPragerViscoplastic(ParameterHandler & prm,
                              const std::string &name,
                              const std::string &section_path);

    void
    update_stress(const StepKinematics &   kinematics,
                  SymmetricTensor<2, 3> &  stress,
                  const ArrayView<double> &internal_variables) const override;

    /** The slope m of the cone q = m p. */
    double
    cone_slope() const
    {
      return m;
    }

  protected:
    /**
     * Return the trial deviator to the viscoplastic state of the step at
     * pressure p > 0 and shear modulus G: the new deviator, and de added
     * to the plastic strain. Separate from the pressure, so that a law with
     * its own pressure ([W] eq. 24) can reuse it.
     */
    std::pair<SymmetricTensor<2, 3>, double>
    viscoplastic_return(const SymmetricTensor<2, 3> &trial_deviator,
                        double                       p,
                        double                       G,
                        double                       dt) const;

  private:
    double m;
    double viscosity;
    double exponent;
  };
} // namespace mpm

#endif
