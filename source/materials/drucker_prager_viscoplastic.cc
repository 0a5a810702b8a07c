#include <mpm/base/input_error.h>
#include <mpm/materials/drucker_prager_viscoplastic.h>

#include <cmath>

namespace mpm
{
  void
  DruckerPragerViscoplastic::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Drucker-Prager viscoplastic");
    prm.declare_entry("Friction angle", "30", Patterns::Double(0., 89.),
                      "Angle of internal friction phi [degrees]; the cone "
                      "is q = m p, m = 18 sin(phi) / (9 - sin^2(phi)).");
    prm.declare_entry("Viscosity parameter", "50", Patterns::Double(0.),
                      "gamma [1/s] of the Perzyna flow: the larger, the "
                      "closer to rate-independent plasticity.");
    prm.declare_entry("Exponent", "1", Patterns::Double(0.),
                      "N > 0 of Phi = ((q - m p) / (m p))^N.");
    prm.leave_subsection();
  }



  DruckerPragerViscoplastic::DruckerPragerViscoplastic(
    ParameterHandler & prm,
    const std::string &name,
    const std::string &section_path)
    : LinearElastic(prm, name, section_path)
  {
    prm.enter_subsection("Drucker-Prager viscoplastic");
    const double sin_phi =
      std::sin(prm.get_double("Friction angle") * numbers::PI / 180.);
    viscosity = prm.get_double("Viscosity parameter");
    exponent  = prm.get_double("Exponent");
    prm.leave_subsection();
    const std::string here = section_path + "/Drucker-Prager viscoplastic/";
    if (!(sin_phi > 0.))
      throw InputError(here + "Friction angle must be positive: the law "
                              "has no cohesion.");
    if (!(viscosity > 0.))
      throw InputError(here + "Viscosity parameter must be positive.");
    if (!(exponent > 0.))
      throw InputError(here + "Exponent must be positive.");
    m              = 18. * sin_phi / (9. - sin_phi * sin_phi);
    internal_names = {"plastic_strain"};
  }



  std::pair<SymmetricTensor<2, 3>, double>
  DruckerPragerViscoplastic::viscoplastic_return(
    const SymmetricTensor<2, 3> &trial_deviator,
    const double                 p,
    const double                 G,
    const double                 dt) const
  {
    const double q_trial = std::sqrt(1.5 * (trial_deviator * trial_deviator));
    const double excess  = q_trial - m * p;
    if (excess <= 0.)
      return {trial_deviator, 0.};

    // Eq. (22): r(de) = de - gamma dt ((excess - 3 G de) / (m p))^N = 0 on
    // [0, excess / 3G], where r rises from negative to positive.
    const double c = viscosity * dt;
    double       de;
    if (exponent == 1.)
      de = excess / (3. * G + m * p / c);
    else
      {
        double low = 0., high = excess / (3. * G);
        de = 0.5 * high;
        for (unsigned int iteration = 0; iteration < 100; ++iteration)
          {
            const double ratio    = (excess - 3. * G * de) / (m * p);
            const double residual = de - c * std::pow(ratio, exponent);
            (residual < 0. ? low : high) = de;
            const double slope =
              1. + c * exponent * std::pow(ratio, exponent - 1.) * 3. * G /
                     (m * p);
            double next = de - residual / slope;
            // Newton inside the bracket, else bisection.
            if (!(next > low && next < high))
              next = 0.5 * (low + high);
            const bool converged = std::abs(next - de) <= 1e-15 * high;
            de                   = next;
            if (converged)
              break;
          }
      }
    const double q = q_trial - 3. * G * de;
    return {trial_deviator * (q / q_trial), de};
  }



  void
  DruckerPragerViscoplastic::update_stress(
    const StepKinematics &   kinematics,
    SymmetricTensor<2, 3> &  stress,
    const ArrayView<double> &internal_variables) const
  {
    // Elastic predictor: Jaumann-rate hypoelasticity, eqs. (15), (17), (20).
    LinearElastic::update_stress(kinematics, stress, internal_variables);
    const double p = -trace(stress) / 3.;
    if (p <= 0.)
      {
        stress = 0;
        return;
      }
    const auto [returned_deviator, de] =
      viscoplastic_return(deviator(stress), p, mu, kinematics.dt);
    stress = returned_deviator - p * unit_symmetric_tensor<3>();
    internal_variables[0] += de;
  }



  MPM_REGISTER_MATERIAL(DruckerPragerViscoplastic,
                        "Drucker-Prager viscoplastic",
                        "Wieckowski's (2004) cohesionless Perzyna law with "
                        "the Jaumann rate (its subsection).",
                        &DruckerPragerViscoplastic::declare_parameters)
} // namespace mpm
