#ifndef mpm_materials_mohr_coulomb_h
#define mpm_materials_mohr_coulomb_h

#include <mpm/materials/hencky_plasticity.h>

#include <boost/container/static_vector.hpp>

namespace mpm
{
  /**
   * Mohr-Coulomb with Hencky elasticity at finite strain
   * (HenckyPlasticity). With the principal Kirchhoff stresses ordered
   * tau_1 >= tau_2 >= tau_3 (tension positive), the yield function is
   * f = k tau_1 - tau_3 - 2 c sqrt(k), k = (1 + sin phi) / (1 - sin phi),
   * and the plastic potential g = m tau_1 - tau_3 with m from the
   * dilatancy angle psi (non-associated for psi < phi). phi = 0 is Tresca.
   *
   * Options:
   * - a tension cut-off (Rankine, tau_1 <= t) with an associated flow;
   * - linear softening of c and phi from their peak to their residual
   *   values as the equivalent plastic strain grows to a given value. The
   *   softening is explicit in the plastic strain: a step returns to the
   *   surface of the plastic strain at its start, so each return stays
   *   exact for linear surfaces and its tangent stays consistent. psi is
   *   capped at the current phi.
   *
   * The return in principal stress space follows Clausen, Damkilde and
   * Andersen (2006, 2007): every surface is a plane in the ordered frame,
   * so the return is to one plane, to the line of two or to the point of
   * three, sigma = sigma_trial - sum_i gamma_i D b_i with a_i . sigma =
   * r_i, and it is the first of these (fewest planes first) with
   * gamma_i >= 0 that lands in the ordered, admissible set. Without a
   * cut-off below it, the apex tau = c cot(phi) closes the list. Each
   * return has the algorithmic tangent D - D B (A^T D B)^-1 A^T D (zero at
   * the apex). The equivalent plastic strain grows by sqrt(2/3 |d eps_p|^2)
   * of the principal plastic strain step.
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
                            double              plastic_strain,
                            bool                with_tangent) const override;

    double
    yield_function(const Tensor<1, 3> &tau,
                   double              plastic_strain) const override;

  private:
    /**
     * A yield plane a . sigma <= r with flow direction b, and what every
     * return to it needs, worked out with the plane: D b, D a (for the
     * tangent), |a| and |a| |D b|, the scale of a . D b, with D the
     * principal elastic stiffness.
     */
    struct Plane
    {
      Plane(const Tensor<1, 3> &a,
            const Tensor<1, 3> &b,
            double              r,
            const Tensor<2, 3> &D);

      Tensor<1, 3> a;
      Tensor<1, 3> b;
      double       r;
      Tensor<1, 3> Db;
      Tensor<1, 3> Da;
      double       a_norm;
      double       scale;
    };

    /**
     * The planes in the ordered frame at a plastic strain: the Mohr-Coulomb
     * plane, the planes that meet it at the edges tau_1 = tau_2 and
     * tau_2 = tau_3, then, with a cut-off, tau_1, tau_2, tau_3 <= t.
     */
    /** At most three planes and three cut-offs; no allocation per point. */
    using Planes = boost::container::static_vector<Plane, 6>;

    Planes
    planes(double plastic_strain) const;

    /** The planes of `strength` (c, phi). */
    Planes
    planes_of(const std::pair<double, double> &strength) const;

    /** max_i (a_i . sigma - r_i) over the planes, sigma sorted descending. */
    static double
    largest_violation(const Planes &      surfaces,
                      const Tensor<1, 3> &      tau);

    /** Cohesion and friction angle at a plastic strain (softening). */
    std::pair<double, double>
    strength(double plastic_strain) const;

    double peak_cohesion;
    double residual_cohesion;
    double peak_friction_angle;
    double residual_friction_angle;
    double dilatancy_angle;
    /** Plastic strain at which the residual strength is reached; 0: none. */
    double softening_plastic_strain;
    bool   tension_cut_off;
    double tensile_strength;
    /** The planes before any softening, kept: their sines are not cheap. */
    Planes peak_planes;

    /** A set of planes a return may rest on: their indices and number. */
    struct ActiveSet
    {
      std::array<unsigned int, 3> planes;
      unsigned int                n;
    };

    /**
     * The sets a return tries, in order; the first admissible one is the
     * return. Softening changes the planes, not their sets.
     */
    boost::container::static_vector<ActiveSet, 41> active_sets;

    /**
     * The inverse of M_ij = a_i . D b_j over the n planes of a set (the
     * first n rows and columns), or `singular`.
     */
    struct SetInverse
    {
      double M_inverse[3][3];
      bool   singular;
    };

    static SetInverse
    invert_set(const Planes &surfaces, const ActiveSet &set);

    /**
     * invert_set() of every active set on the peak planes, worked out once:
     * without softening a return reads them instead of inverting.
     */
    boost::container::static_vector<SetInverse, 41> peak_inverses;
  };
} // namespace mpm

#endif
