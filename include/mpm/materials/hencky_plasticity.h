#ifndef mpm_materials_hencky_plasticity_h
#define mpm_materials_hencky_plasticity_h

#include <mpm/materials/material.h>

namespace mpm
{
  /**
   * Elastoplasticity at finite strain by the multiplicative split
   * F = F_e F_p with Hencky elasticity, integrated by the exponential map
   * (Simo 1992): the trial elastic left Cauchy-Green tensor
   * b_e = f b_e,n f^T, f = F_new F_old^-1 = I + dt L (as StepKinematics
   * defines L; the latter, with no inverse), gives principal logarithmic
   * strains eps_a = ln(lambda_a); the Kirchhoff stress tau_a = D eps_a is
   * linear in them, so a law returns its principal trial stress to the
   * yield surface exactly as in small strain ("return_to_yield_surface"),
   * and b_e is rebuilt from the returned elastic strains. The step is
   * objective: a rigid rotation of the step rotates b_e and the stress and
   * changes no invariant.
   *
   * Internal variables: the equivalent plastic strain, then b_e - I (6
   * entries, so that zero is the natural state).
   *
   * The spatial tangent is the consistent one: with D_alg = d tau_a /
   * d eps_b from the return, in the eigenbasis n_a of b_e,
   * c_tau = sum_ab (D_alg_ab - 2 tau_a delta_ab) m_a (x) m_b
   *       + sum_a<b 2 g_ab s_ab (x) s_ab,
   * g_ab = 2 (tau_a beta_b - tau_b beta_a) / (beta_a - beta_b), where
   * beta_a = lambda_a^2, m_a = n_a (x) n_a, s_ab = sym(n_a (x) n_b); for
   * equal beta the limit g_ab = D_alg_aa - D_alg_ab - 2 tau_a.
   */
  class HenckyPlasticity : public Material
  {
  public:
    /**
     * Index of the equivalent plastic strain among the internal ones: the
     * first, as in every plastic law, so that a scene that mixes laws
     * shows it under one name.
     */
    static constexpr unsigned int equivalent_plastic_strain = 0;
    /** Index of the first of the 6 entries of b_e - I. */
    static constexpr unsigned int elastic_b_minus_I = 1;

    void
    update_stress(const StepKinematics &   kinematics,
                  SymmetricTensor<2, 3> &  stress,
                  const ArrayView<double> &internal_variables) const override;

    SymmetricTensor<4, 3>
    spatial_tangent(const StepKinematics &         kinematics,
                    const SymmetricTensor<2, 3> &  old_stress,
                    const ArrayView<const double> &old_internal_variables)
      const override;

    /**
     * b_e from the stress (Kirchhoff = Cauchy at F = I); a stress outside
     * the yield surface is refused.
     */
    double
    initialize_stress(const SymmetricTensor<2, 3> &stress,
                      const ArrayView<double> &    internal_variables,
                      const std::string &          who) const override;

    /** The result of a return in principal stress space. */
    struct Return
    {
      /** Principal Kirchhoff stresses, in the order of the trial ones. */
      Tensor<1, 3> tau;
      /** d tau_a / d eps_trial_b, if asked for (else zero). */
      Tensor<2, 3> tangent;
      /** Increment of the equivalent plastic strain. */
      double plastic_strain_increment = 0.;
      /** Whether the trial state was returned (false: it is admissible). */
      bool plastic = false;
    };

    /**
     * Return the principal trial Kirchhoff stress (tension positive, any
     * order) to the yield surface, given the equivalent plastic strain at
     * the start of the step. Elastic states come back unchanged (with
     * tangent D). The tangent is worked out only `with_tangent`: the
     * explicit scheme needs none.
     */
    virtual Return
    return_to_yield_surface(const Tensor<1, 3> &trial_tau,
                            double              plastic_strain,
                            bool                with_tangent) const = 0;

    /**
     * The yield function at a principal Kirchhoff stress: <= 0 is
     * admissible. For the tests and for checks.
     */
    virtual double
    yield_function(const Tensor<1, 3> &tau, double plastic_strain) const = 0;

  protected:
    HenckyPlasticity(const ParameterHandler &prm,
                     const std::string &     name,
                     const std::string &     section_path);

    /**
     * The principal elastic stiffness: lambda + 2 mu on, lambda off; kept,
     * as every step of every point uses it.
     */
    Tensor<2, 3> principal_stiffness;

    /** Its inverse, kept: an elastic strain per plastic return. */
    Tensor<2, 3> principal_compliance;

  private:
    /** The trial state of a step and its return. */
    struct Step
    {
      SymmetricTensor<2, 3>       b_trial;
      Tensor<1, 3>                beta;
      std::array<Tensor<1, 3>, 3> directions;
      Return                      result;
      double                      J;
    };

    /** The return's tangent `with_tangent` only. */
    Step
    compute_step(const StepKinematics &         kinematics,
                 const ArrayView<const double> &old_internal_variables,
                 bool                           with_tangent) const;
  };
} // namespace mpm

#endif
