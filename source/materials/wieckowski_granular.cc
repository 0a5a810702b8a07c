#include <mpm/base/input_error.h>
#include <mpm/materials/wieckowski_granular.h>

#include <algorithm>
#include <cmath>

namespace mpm
{
  void
  WieckowskiGranular::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Wieckowski granular");
    prm.declare_entry("Reference pressure", "600", Patterns::Double(0.),
                      "p0 [Pa]: the pressure of the state from which the "
                      "volume change is measured, at the law's Density (a "
                      "body seeded at it starts there).");
    prm.declare_entry("Reference void ratio", "0.9", Patterns::Double(0.),
                      "e0: the void ratio of that state. The Density entry "
                      "is the bulk density, rho_s / (1 + e0).");
    prm.declare_entry("Elastic coefficient", "0.02", Patterns::Double(0.),
                      "kappa of e - e0 = -kappa ln(p / p0).");
    prm.declare_entry("Bulk viscosity", "1e4", Patterns::Double(0.),
                      "mu_v [Pa s]: the pressure gains (-mu_v tr D)^+ in "
                      "compression. It also bounds the explicit step, "
                      "dt < rho h^2 / (2 mu_v), which the automatic step "
                      "takes into account.");
    prm.declare_entry("Density from positions", "false", Patterns::Bool(),
                      "true: the density of a point, and so its volume "
                      "ratio J = rho_ref / rho to the reference state, is "
                      "interpolated from nodal densities, the lumped nodal "
                      "mass over the volume of the node's cells that hold "
                      "material ([W] eqs. 12-13): a smooth pressure in a "
                      "fill built from loose portions. false: the point's "
                      "mass over its current volume (eq. 11). Explicit "
                      "scheme only.");
    prm.leave_subsection();
  }



  WieckowskiGranular::WieckowskiGranular(ParameterHandler & prm,
                                         const std::string &name,
                                         const std::string &section_path)
    : DruckerPragerViscoplastic(prm, name, section_path)
  {
    prm.enter_subsection("Wieckowski granular");
    reference_pressure        = prm.get_double("Reference pressure");
    const double void_ratio   = prm.get_double("Reference void ratio");
    const double kappa        = prm.get_double("Elastic coefficient");
    bulk_viscosity            = prm.get_double("Bulk viscosity");
    density_from_positions    = prm.get_bool("Density from positions");
    prm.leave_subsection();
    const std::string here = section_path + "/Wieckowski granular/";
    if (!(reference_pressure > 0.))
      throw InputError(here + "Reference pressure must be positive.");
    if (!(void_ratio > 0.))
      throw InputError(here + "Reference void ratio must be positive.");
    if (!(kappa > 0.))
      throw InputError(here + "Elastic coefficient must be positive.");
    compression_ratio = (1. + void_ratio) / kappa;
    shear_to_bulk =
      1.5 * (1. - 2. * poissons_ratio) / (1. + poissons_ratio);
    internal_names = {"plastic_strain", "volumetric_strain"};
  }



  double
  WieckowskiGranular::elastic_pressure(const double J) const
  {
    return reference_pressure * std::exp(compression_ratio * (1. - J));
  }



  bool
  WieckowskiGranular::separated(const double J) const
  {
    return elastic_pressure(J) < 1e-6 * reference_pressure;
  }



  double
  WieckowskiGranular::bulk_modulus(const double J) const
  {
    return compression_ratio * elastic_pressure(J) * J;
  }



  void
  WieckowskiGranular::update_stress(
    const StepKinematics &   kinematics,
    SymmetricTensor<2, 3> &  stress,
    const ArrayView<double> &internal_variables) const
  {
    const Tensor<2, 3> &        L = kinematics.velocity_gradient;
    const SymmetricTensor<2, 3> D = symmetrize(L);
    // The volume ratio to the reference state, rho_ref / rho: a point
    // seeded loose (below the law's Density) starts expanded.
    const double rho = density_from_positions ? kinematics.grid_fields[0] :
                                                kinematics.density;
    const double J   = rho > 0. ? density() / rho : determinant(kinematics.F_new);
    internal_variables[1]         = std::log(J);
    if (separated(J))
      {
        stress = 0;
        return;
      }
    const double p = elastic_pressure(J) +
                     std::max(0., -bulk_viscosity * trace(D));
    const double G = shear_to_bulk * bulk_modulus(J);

    // Deviatoric predictor, eqs. (16)-(18) with the Jaumann rate.
    const SymmetricTensor<2, 3> s_old = deviator(stress);
    const SymmetricTensor<2, 3> trial =
      s_old +
      kinematics.dt * (2. * G * deviator(D) + jaumann_rotation(L, s_old));
    const auto [s, de] = viscoplastic_return(trial, p, G, kinematics.dt);
    stress = s - p * unit_symmetric_tensor<3>();
    internal_variables[0] += de;
  }



  SymmetricTensor<2, 3>
  WieckowskiGranular::seeded_state(
    const double             density,
    const ArrayView<double> &internal_variables) const
  {
    const double J        = this->density() / density;
    internal_variables[1] = std::log(J);
    if (separated(J))
      return {};
    return -elastic_pressure(J) * unit_symmetric_tensor<3>();
  }



  double
  WieckowskiGranular::initialize_stress(const SymmetricTensor<2, 3> &,
                                        const ArrayView<double> &,
                                        const std::string &who) const
  {
    throw InputError(who + ": material '" + name() +
                     "' (Wieckowski granular) takes its pressure from the "
                     "volume change alone, so it starts at p0 from the "
                     "seeded state; use Initial stress = none.");
  }



  double
  WieckowskiGranular::signal_speed(
    const SymmetricTensor<2, 3> &,
    const ArrayView<const double> &internal_variables,
    const double                   cell_size) const
  {
    const double J = std::exp(internal_variables[1]);
    if (separated(J))
      return 0.;
    const double K = bulk_modulus(J);
    const double current_density = density() / J;
    return std::sqrt((K + 4. / 3. * shear_to_bulk * K) / current_density) +
           2. * bulk_viscosity / (current_density * cell_size);
  }



  MPM_REGISTER_MATERIAL(WieckowskiGranular,
                        "Wieckowski granular",
                        "his law for loose fill, eq. (24): pressure "
                        "exponential in the volume change plus bulk "
                        "viscosity, shear modulus proportional to the "
                        "pressure, deviator as 'Drucker-Prager "
                        "viscoplastic' (both subsections; Young's modulus "
                        "is not used).",
                        &WieckowskiGranular::declare_parameters)
} // namespace mpm
