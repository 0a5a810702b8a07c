#include <mpm/base/input_error.h>
#include <mpm/materials/von_mises.h>

#include <cmath>

namespace mpm
{
  void
  VonMises::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("von Mises");
    prm.declare_entry("Yield stress", "1e6", Patterns::Double(0.),
                      "Initial yield stress sigma_y in uniaxial tension "
                      "[Pa].");
    prm.declare_entry("Hardening modulus", "0", Patterns::Double(0.),
                      "Linear isotropic hardening H [Pa]: the yield stress "
                      "is sigma_y + H eps_p.");
    prm.leave_subsection();
  }



  VonMises::VonMises(ParameterHandler & prm,
                     const std::string &name,
                     const std::string &section_path)
    : HenckyPlasticity(prm, name, section_path)
  {
    prm.enter_subsection("von Mises");
    yield_stress      = prm.get_double("Yield stress");
    hardening_modulus = prm.get_double("Hardening modulus");
    prm.leave_subsection();
    if (!(yield_stress > 0.))
      throw InputError(section_path + "/von Mises/Yield stress must be "
                                      "positive.");
  }



  double
  VonMises::yield_function(const Tensor<1, 3> &tau,
                           const double        plastic_strain) const
  {
    const double p = (tau[0] + tau[1] + tau[2]) / 3.;
    Tensor<1, 3> s = tau;
    for (unsigned int a = 0; a < 3; ++a)
      s[a] -= p;
    return std::sqrt(1.5) * s.norm() -
           (yield_stress + hardening_modulus * plastic_strain);
  }



  HenckyPlasticity::Return
  VonMises::return_to_yield_surface(const Tensor<1, 3> &trial_tau,
                                    const double        plastic_strain,
                                    const bool          with_tangent) const
  {
    Return r;
    r.tau = trial_tau;
    if (with_tangent)
      r.tangent = principal_stiffness;
    const double f = yield_function(trial_tau, plastic_strain);
    if (f <= 0.)
      return r;
    r.plastic = true;

    const double p = (trial_tau[0] + trial_tau[1] + trial_tau[2]) / 3.;
    Tensor<1, 3> s = trial_tau;
    for (unsigned int a = 0; a < 3; ++a)
      s[a] -= p;
    const double q      = std::sqrt(1.5) * s.norm();
    const double gamma  = f / (3. * mu + hardening_modulus);
    const double factor = 1. - 3. * mu * gamma / q;
    const Tensor<1, 3> n = s / s.norm();
    const double       K = lambda + 2. / 3. * mu;
    for (unsigned int a = 0; a < 3; ++a)
      {
        r.tau[a] = p + factor * s[a];
        for (unsigned int b = 0; b < 3 && with_tangent; ++b)
          r.tangent[a][b] =
            K + 2. * mu * factor * ((a == b ? 1. : 0.) - 1. / 3.) +
            6. * mu * mu * (gamma / q - 1. / (3. * mu + hardening_modulus)) *
              n[a] * n[b];
      }
    r.plastic_strain_increment = gamma;
    return r;
  }



  MPM_REGISTER_MATERIAL(VonMises,
                        "von Mises",
                        "elastoplastic (J2) at finite strain with Hencky "
                        "elasticity (its subsection).",
                        &VonMises::declare_parameters)
} // namespace mpm
