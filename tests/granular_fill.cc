// Wieckowski's (2004) law for loose granular fill, eq. (24), on stress
// paths with a known answer:
// - isotropic compression and expansion at a constant rate, F = exp(r t) I:
//   the elastic pressure follows the void-ratio law e - e0 = -kappa
//   ln(p / p0) with e = (1 + e0) J - 1, evaluated here independently; in
//   compression the pressure gains mu_v |tr D|, in expansion nothing; the
//   deviator stays zero;
// - a small shear step at a compressed state J: q = 3 G r_eq dt with
//   G = 3/2 (1 - 2 nu)/(1 + nu) (1 + e0)/kappa p J, so G / p is constant
//   along the path and G / K = 3 (1 - 2 nu) / (2 (1 + nu));
// - long pure shear at fixed volume: the Drucker-Prager steady state
//   q = m p (1 + r_eq / gamma) for N = 1 with p = p_el(J);
// - the explicit step sees the stiffness of the state: signal_speed equals
//   sqrt((K + 4/3 G) / rho) + 2 mu_v / (rho h) with rho = rho0 / J;
// - a point expanded until p_el < 1e-6 p0 (J = 1.2) has come apart: no
//   stress, not even from a compression rate, and no limit on the step;
// - a seeded point starts in the reference state, -p0 I, and a step without
//   motion keeps it there;
// - a geostatic start is refused with a message.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/base/input_error.h>
#include <mpm/materials/wieckowski_granular.h>

#include <cmath>

#include "tests.h"

using namespace dealii;
using namespace mpm;

// [W] 5.1.2: kappa = 0.02, nu = 0.3, e0 = 0.9, p0 = 600 Pa, phi = 30,
// mu_v = 1e4 Pa s, gamma = 1e4 1/s (here 10, to see the excess), N = 1.
const double kappa = 0.02, nu = 0.3, e0 = 0.9, p0 = 600., mu_v = 1e4,
             gamma_ = 10., rho0 = 1500.;

std::unique_ptr<WieckowskiGranular>
make()
{
  ParameterHandler prm;
  Material::declare_parameters(prm);
  prm.set("Model", "Wieckowski granular");
  prm.set("Density", std::to_string(rho0));
  prm.set("Poisson's ratio", std::to_string(nu));
  prm.enter_subsection("Drucker-Prager viscoplastic");
  prm.set("Friction angle", "30");
  prm.set("Viscosity parameter", std::to_string(gamma_));
  prm.leave_subsection();
  prm.enter_subsection("Wieckowski granular");
  prm.set("Reference pressure", std::to_string(p0));
  prm.set("Reference void ratio", std::to_string(e0));
  prm.set("Elastic coefficient", std::to_string(kappa));
  prm.set("Bulk viscosity", std::to_string(mu_v));
  prm.leave_subsection();
  auto material = Material::create(prm, "fill", "Materials/fill");
  return std::unique_ptr<WieckowskiGranular>(
    dynamic_cast<WieckowskiGranular *>(material.release()));
}

/** Pressure of the void-ratio law at volume ratio J. */
double
void_ratio_pressure(const double J)
{
  const double e = (1 + e0) * J - 1;
  return p0 * std::exp(-(e - e0) / kappa);
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  const auto law = make();
  const double m = law->cone_slope();
  deallog << "m = " << m << ", internal variables:";
  for (const auto &name : law->internal_variable_names())
    deallog << ' ' << name;
  deallog << std::endl;

  // Isotropic paths at rate r, F = exp(r t) I, to J = 0.97 and J = 1.02.
  for (const double r : {-0.3, 0.2})
    {
      StepKinematics k;
      k.dt = 1e-4;
      for (unsigned int d = 0; d < 3; ++d)
        k.velocity_gradient[d][d] = r;
      SymmetricTensor<2, 3> stress;
      std::vector<double>   internal(2, 0.);
      double                pressure_error = 0., deviator_norm = 0., J = 1.;
      for (unsigned int step = 1; step <= 1000; ++step)
        {
          const double F_old = std::exp(r * (step - 1) * k.dt);
          const double F_new = std::exp(r * step * k.dt);
          k.F_old            = F_old * Tensor<2, 3>(unit_symmetric_tensor<3>());
          k.F_new            = F_new * Tensor<2, 3>(unit_symmetric_tensor<3>());
          law->update_stress(k, stress,
                             ArrayView<double>(internal.data(), 2));
          J = F_new * F_new * F_new;
          const double expected =
            void_ratio_pressure(J) + (r < 0 ? mu_v * 3 * -r : 0.);
          pressure_error = std::max(
            pressure_error, std::abs(-trace(stress) / 3 - expected) / expected);
          deviator_norm = std::max(deviator_norm, deviator(stress).norm());
        }
      const std::string path = r < 0 ? "compression" : "expansion";
      deallog << path << " to J = " << J << ": p = " << -trace(stress) / 3
              << " Pa" << std::endl;
      mpm_tests::check("isotropic " + path +
                         ": p = p0 exp(-(e - e0)/kappa) " +
                         (r < 0 ? "+ mu_v |tr D|" : "(no viscous part)") +
                         " to 1e-12, no deviator",
                       pressure_error < 1e-12 && deviator_norm < 1e-9);
      mpm_tests::check("isotropic " + path +
                         ": volumetric_strain = ln J to 1e-12",
                       std::abs(internal[1] - std::log(J)) < 1e-12);
    }

  // Shear modulus proportional to the pressure: one small shear step at
  // several volume ratios.
  {
    double ratio_error = 0.;
    for (const double J : {0.98, 0.99, 1.0, 1.01})
      {
        const double   a = std::cbrt(J);
        StepKinematics k;
        k.dt                      = 1e-6;
        k.F_old = a * Tensor<2, 3>(unit_symmetric_tensor<3>());
        k.velocity_gradient[0][0] = 1.;
        k.velocity_gradient[1][1] = -1.;
        k.F_new = (Tensor<2, 3>(unit_symmetric_tensor<3>()) +
                   k.dt * k.velocity_gradient) *
                  k.F_old;
        SymmetricTensor<2, 3> stress =
          -void_ratio_pressure(J) * unit_symmetric_tensor<3>();
        std::vector<double> internal(2, std::log(J));
        law->update_stress(k, stress, ArrayView<double>(internal.data(), 2));
        const double p_el = void_ratio_pressure(J);
        const double K    = (1 + e0) / kappa * p_el * J;
        const double G    = 1.5 * (1 - 2 * nu) / (1 + nu) * K;
        const double q    = mpm_tests::von_mises_q(stress);
        ratio_error =
          std::max(ratio_error,
                   std::abs(q - 3 * G * (2 / std::sqrt(3.)) * k.dt) / q);
      }
    mpm_tests::check("a shear step gives q = 3 G r_eq dt with G = 3/2 "
                     "(1 - 2 nu)/(1 + nu) (1 + e0)/kappa p J, at J = 0.98 to "
                     "1.01, to 1e-6",
                     ratio_error < 1e-6);
  }

  // Long isochoric pure shear at J = 0.99: the steady state of the cone.
  {
    const double   J = 0.99, a = std::cbrt(J), rate = 0.5;
    StepKinematics k;
    k.dt                      = 1e-5;
    k.velocity_gradient[0][0] = rate;
    k.velocity_gradient[1][1] = -rate;
    Tensor<2, 3> F = a * Tensor<2, 3>(unit_symmetric_tensor<3>());
    SymmetricTensor<2, 3> stress =
      -void_ratio_pressure(J) * unit_symmetric_tensor<3>();
    std::vector<double> internal(2, std::log(J));
    for (unsigned int step = 0; step < 20000; ++step)
      {
        k.F_old = F;
        F[0][0] *= std::exp(rate * k.dt);
        F[1][1] *= std::exp(-rate * k.dt);
        k.F_new = F;
        law->update_stress(k, stress, ArrayView<double>(internal.data(), 2));
      }
    const double p      = void_ratio_pressure(determinant(F));
    const double steady = m * p * (1 + 2 * rate / std::sqrt(3.) / gamma_);
    deallog << "isochoric shear: q = " << mpm_tests::von_mises_q(stress)
            << " Pa, steady state " << steady << " Pa, plastic strain "
            << internal[0] << std::endl;
    mpm_tests::check("isochoric shear: q = m p (1 + r_eq / gamma) to 1e-6",
                     std::abs(mpm_tests::von_mises_q(stress) - steady) <
                       1e-6 * steady);
  }

  // The explicit step follows the state.
  {
    const double h = 0.05, J = 0.97;
    std::vector<double> internal = {0., std::log(J)};
    const double K   = (1 + e0) / kappa * void_ratio_pressure(J) * J;
    const double G   = 1.5 * (1 - 2 * nu) / (1 + nu) * K;
    const double rho = rho0 / J;
    const double expected =
      std::sqrt((K + 4. / 3. * G) / rho) + 2 * mu_v / (rho * h);
    const double speed = law->signal_speed(
      SymmetricTensor<2, 3>(), ArrayView<const double>(internal.data(), 2), h);
    deallog << "signal speed at J = 0.97, h = 0.05: " << speed << " m/s"
            << std::endl;
    mpm_tests::check("signal speed = sqrt((K + 4/3 G)/rho) + 2 mu_v/(rho h) "
                     "to 1e-12",
                     std::abs(speed - expected) < 1e-12 * expected);
  }

  // Come apart.
  {
    const double   a = std::cbrt(1.2);
    StepKinematics k;
    k.dt = 1e-4;
    k.F_old = k.F_new = a * Tensor<2, 3>(unit_symmetric_tensor<3>());
    for (unsigned int d = 0; d < 3; ++d)
      k.velocity_gradient[d][d] = -1.;
    SymmetricTensor<2, 3> stress = -100. * unit_symmetric_tensor<3>();
    std::vector<double>   internal(2, 0.);
    law->update_stress(k, stress, ArrayView<double>(internal.data(), 2));
    const double speed = law->signal_speed(
      stress, ArrayView<const double>(internal.data(), 2), 0.05);
    mpm_tests::check("at J = 1.2 (p_el < 1e-6 p0) the fill has come apart: "
                     "no stress under a compression rate, signal speed 0",
                     stress.norm() == 0. && speed == 0.);
  }

  // The seeded state.
  {
    StepKinematics k;
    k.dt = 1e-4;
    k.F_old = k.F_new = Tensor<2, 3>(unit_symmetric_tensor<3>());
    std::vector<double>         internal(2, 0.);
    const SymmetricTensor<2, 3> seeded = law->seeded_state(
      law->density(), ArrayView<double>(internal.data(), 2));
    SymmetricTensor<2, 3> stress = seeded;
    law->update_stress(k, stress, ArrayView<double>(internal.data(), 2));
    const SymmetricTensor<2, 3> p0_I = p0 * unit_symmetric_tensor<3>();
    mpm_tests::check("a seeded point is at -p0 I and stays there without "
                     "motion, to 1e-12",
                     (seeded + p0_I).norm() < 1e-12 * p0 &&
                       (stress + p0_I).norm() < 1e-12 * p0);
  }

  // A geostatic start is refused.
  {
    std::vector<double> internal(2, 0.);
    bool                refused = false;
    try
      {
        law->initialize_stress(-1000. * unit_symmetric_tensor<3>(),
                               ArrayView<double>(internal.data(), 2),
                               "Bodies/heap");
      }
    catch (const InputError &e)
      {
        refused = true;
        deallog << e.what() << std::endl;
      }
    mpm_tests::check("a geostatic start is refused with a message", refused);
  }
}
