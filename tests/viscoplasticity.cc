// The Drucker-Prager viscoplastic law of Wieckowski (2004), eqs. (15)-(23):
// - pure shear at a constant rate (D = diag(r, -r, 0), no spin) under a
//   pressure p: elastic q = 3 G r_eq t (r_eq = 2 r / sqrt 3) until the cone
//   q = m p; then, for N = 1, the closed form of the continuous law,
//   q = m p + (m p r_eq / gamma) (1 - exp(-3 G gamma (t - t_y) / (m p))),
//   which backward Euler reaches at first order in dt (the error halves
//   with dt) and the pressure stays p;
// - for N = 1 (closed form), 2 and 0.5 (scalar Newton), every step
//   satisfies eq. (22),
//   de = gamma dt ((q - m p) / (m p))^N, to 1e-10, and the stress tends to
//   the steady state q = m p (1 + (r_eq / gamma)^(1/N));
// - a point in tension carries no stress (cohesionless).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/drucker_prager_viscoplastic.h>

#include <cmath>

#include "tests.h"

using namespace dealii;
using namespace mpm;

const double E = 1e6, nu = 0.3, gamma_ = 1., p0 = 1e4, rate = 0.1;
const double G      = E / (2 * (1 + nu));
const double r_eq   = 2 * rate / std::sqrt(3.);

std::unique_ptr<DruckerPragerViscoplastic>
make(const double exponent)
{
  ParameterHandler prm;
  Material::declare_parameters(prm);
  prm.set("Model", "Drucker-Prager viscoplastic");
  prm.set("Young's modulus", std::to_string(E));
  prm.set("Poisson's ratio", std::to_string(nu));
  prm.enter_subsection("Drucker-Prager viscoplastic");
  prm.set("Friction angle", "25");
  prm.set("Viscosity parameter", std::to_string(gamma_));
  prm.set("Exponent", std::to_string(exponent));
  prm.leave_subsection();
  auto material = Material::create(prm, "test", "test");
  return std::unique_ptr<DruckerPragerViscoplastic>(
    dynamic_cast<DruckerPragerViscoplastic *>(material.release()));
}

/** Pure shear to time `end`; calls `observe(t, stress, de)` each step. */
template <typename Observer>
void
shear(const Material &law, const double dt, const double end,
      const Observer &observe)
{
  StepKinematics k;
  k.dt                      = dt;
  k.velocity_gradient[0][0] = rate;
  k.velocity_gradient[1][1] = -rate;
  SymmetricTensor<2, 3> stress = -p0 * unit_symmetric_tensor<3>();
  std::vector<double>   internal(1, 0.);
  const unsigned int    n = static_cast<unsigned int>(std::round(end / dt));
  for (unsigned int step = 1; step <= n; ++step)
    {
      const double before = internal[0];
      law.update_stress(k, stress,
                        ArrayView<double>(internal.data(), internal.size()));
      observe(step * dt, stress, internal[0] - before);
    }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  // N = 1 against the closed form, at two step sizes.
  {
    const auto   law  = make(1.);
    const double mp   = law->cone_slope() * p0;
    const double t_y  = mp / (3 * G * r_eq);
    const double tau  = mp / (3 * G * gamma_);
    const double y_oo = mp * r_eq / gamma_;
    const double end  = t_y + 5 * tau;
    std::vector<double> error(2, 0.);
    double              elastic_error = 0., pressure_error = 0.;
    for (unsigned int refinement = 0; refinement < 2; ++refinement)
      shear(*law, 1e-4 / (1 << refinement), end,
            [&](const double t, const SymmetricTensor<2, 3> &stress,
                const double) {
              const double q = mpm_tests::von_mises_q(stress);
              pressure_error =
                std::max(pressure_error,
                         std::abs(-trace(stress) / 3 - p0) / p0);
              if (t < t_y)
                elastic_error =
                  std::max(elastic_error,
                           std::abs(q - 3 * G * r_eq * t) / mp);
              else
                {
                  const double exact =
                    mp + y_oo * (1 - std::exp(-(t - t_y) / tau));
                  error[refinement] =
                    std::max(error[refinement], std::abs(q - exact) / y_oo);
                }
            });
    deallog << "N = 1: m p = " << mp << " Pa, yield at " << t_y
            << " s, relaxation time " << tau << " s, steady excess " << y_oo
            << " Pa" << std::endl;
    mpm_tests::check("N = 1, pure shear: elastic q = 3 G r_eq t before the "
                     "cone, to 1e-12, at constant pressure",
                     elastic_error < 1e-12 && pressure_error < 1e-12);
    mpm_tests::check("N = 1, pure shear: within 2% of the closed form's "
                     "excess over the cone at dt = 5e-5 s",
                     error[1] < 0.02);
    mpm_tests::check("N = 1, pure shear: first order, the error halves "
                     "with dt (ratio 1.7 to 2.3)",
                     error[0] / error[1] > 1.7 && error[0] / error[1] < 2.3);
  }

  // Eq. (22) at every step (closed form for N = 1, Newton otherwise), and
  // the steady state.
  for (const double N : {1., 2., 0.5})
    {
      const auto   law = make(N);
      const double mp  = law->cone_slope() * p0;
      const double dt  = 1e-4;
      double       equation_error = 0., q_last = 0.;
      unsigned int n_plastic      = 0;
      shear(*law, dt, 2.,
            [&](const double, const SymmetricTensor<2, 3> &stress,
                const double de) {
              q_last = mpm_tests::von_mises_q(stress);
              if (de > 0.)
                {
                  ++n_plastic;
                  const double expected =
                    gamma_ * dt * std::pow((q_last - mp) / mp, N);
                  equation_error =
                    std::max(equation_error, std::abs(de - expected) / de);
                }
            });
      const double steady = mp * (1 + std::pow(r_eq / gamma_, 1 / N));
      mpm_tests::check("N = " + std::to_string(N).substr(0, 3) +
                         ": every viscoplastic step solves eq. (22) to "
                         "1e-10",
                       equation_error < 1e-10 && n_plastic > 1000);
      mpm_tests::check("N = " + std::to_string(N).substr(0, 3) +
                         ": steady state q = m p (1 + (r_eq / gamma)^(1/N)) "
                         "to 1e-6",
                       std::abs(q_last - steady) / steady < 1e-6);
    }

  // Tension.
  {
    const auto     law = make(1.);
    StepKinematics k;
    k.dt                      = 1e-3;
    k.velocity_gradient[0][0] = 1.;
    k.velocity_gradient[0][1] = 0.3;
    SymmetricTensor<2, 3> stress;
    std::vector<double>   internal(1, 0.);
    law->update_stress(k, stress,
                       ArrayView<double>(internal.data(), internal.size()));
    mpm_tests::check("a point stretched into tension carries no stress",
                     stress.norm() == 0.);
  }
}
