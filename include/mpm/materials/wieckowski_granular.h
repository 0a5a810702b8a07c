#ifndef mpm_materials_wieckowski_granular_h
#define mpm_materials_wieckowski_granular_h

#include <mpm/materials/drucker_prager_viscoplastic.h>

namespace mpm
{
  /**
   * Wieckowski's (2004) law for loose granular fill, section 5.1.2. The
   * pressure is that of eq. (24),
   *   p = p0 exp((1 + e0)/kappa (1 - J)) + (-mu_v tr D)^+,
   * with J = exp(eps_vol) = rho_ref / rho the volume ratio to the state
   * (p0, e0), rho_ref the law's Density and rho the point's (seeded at
   * another bulk density, a point starts at its J; with `Density from
   * positions`, rho is that of [W] eqs. 12-13); its
   * elastic part is the void-ratio law e - e0 = -kappa ln(p/p0) and is
   * evaluated in closed form from J (no drift), the viscous part from the
   * step's rate. The deviator is that of the Drucker-Prager viscoplastic
   * law (Jaumann rate, Perzyna return, its subsection) with the shear
   * modulus of the elastic pressure,
   *   G = 3/2 (1 - 2 nu)/(1 + nu) K,  K = (1 + e0)/kappa p_el J,
   * so stiffness grows with pressure and `Young's modulus` is not used.
   * The explicit step follows the stiffest point (signal_speed). A point
   * expanded until its elastic pressure is below 1e-6 p0 has come apart and
   * carries no stress (separated()). Internal
   * variables: `plastic_strain` and `volumetric_strain` (ln J).
   */
  class WieckowskiGranular : public DruckerPragerViscoplastic
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    WieckowskiGranular(ParameterHandler & prm,
                       const std::string &name,
                       const std::string &section_path);

    void
    update_stress(const StepKinematics &   kinematics,
                  SymmetricTensor<2, 3> &  stress,
                  const ArrayView<double> &internal_variables) const override;

    /** Refused: the pressure follows from the volume change alone. */
    double
    initialize_stress(const SymmetricTensor<2, 3> &stress,
                      const ArrayView<double> &    internal_variables,
                      const std::string &          who) const override;

    double
    signal_speed(const SymmetricTensor<2, 3> &  stress,
                 const ArrayView<const double> &internal_variables,
                 const double                   cell_size) const override;

    /**
     * A point seeded at density rho has J = rho_ref / rho and its elastic
     * pressure: -p0 I at the law's Density, none in a loose portion.
     */
    SymmetricTensor<2, 3>
    seeded_state(const double             density,
                 const ArrayView<double> &internal_variables) const override;

    /** The pressure follows the volume ratio rho_ref / rho. */
    bool
    stress_follows_density() const override
    {
      return true;
    }

    /** With Density from positions, the grid field of that name. */
    std::vector<std::string>
    grid_fields() const override
    {
      if (density_from_positions)
        return {"Density from positions"};
      return {};
    }

    /** Elastic pressure p0 exp((1 + e0)/kappa (1 - J)). */
    double
    elastic_pressure(const double J) const;

    /**
     * Whether the fill has come apart at volume ratio J: its elastic
     * pressure is below 1e-6 p0 (a void ratio above e0 + 13.8 kappa). It
     * then carries no stress, viscous or elastic, as the viscoplastic law in
     * tension, and sets no limit on the time step.
     */
    bool
    separated(const double J) const;

    /** Bulk modulus of the elastic pressure, (1 + e0)/kappa p_el J. */
    double
    bulk_modulus(const double J) const;

  private:
    double reference_pressure;
    double compression_ratio; // (1 + e0) / kappa
    double bulk_viscosity;
    double shear_to_bulk; // 3/2 (1 - 2 nu)/(1 + nu)
    bool   density_from_positions;
  };
} // namespace mpm

#endif
