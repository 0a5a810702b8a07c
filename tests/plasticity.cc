// The elastoplastic laws (Hencky elasticity, exponential-map return):
// - after every return from 4500 random trial states (random stretches and
//   rotations from random earlier plastic states) the stress is on or
//   inside the yield surface to 1e-10 of its size, for Mohr-Coulomb
//   (associated and not, softening, with a tension cut-off) and von Mises
//   (perfect and hardening); the Mohr-Coulomb returns visit the plane,
//   both edges (at least 10 returns to each, counted apart) and the apex,
//   or with the cut-off its plane and corner;
// - the consistent tangent (closed form, HenckyPlasticity) matches central
//   differences of the stress update to 1e-6 at elastic, plane, edge and
//   apex states, and after an earlier plastic step with a rotation;
// - von Mises in uniaxial strain eps (log): yields at 2 mu |eps| = sigma_y
//   (q = 2 mu |eps| on this path); beyond it tau_xx - tau_yy = sigma_y +
//   H eps_p, the mean stress stays K tr(eps), and the plastic strain is
//   deviatoric along (2, -1, -1); in biaxial strain (e, e, 0) likewise
//   tau_xx - tau_zz = sigma_y;
// - Mohr-Coulomb in compression along (nu e, nu e, -e), uniaxial stress
//   while elastic: yields at the unconfined strength E e = 2 c sqrt(k),
//   then stays on the triaxial-compression edge, k tau_x - tau_z = 2 c sqrt(k) with tau_x =
//   tau_y, and flows along the two potentials: d eps_p ~ (m, m, -2);
// - Mohr-Coulomb in hydrostatic tension beyond the apex returns to
//   c cot(phi);
// - tension cut-off in uniaxial strain: tau_xx = t and tau_yy = tau_zz =
//   lambda t / (lambda + 2 mu) once it yields;
// - softening: each step on the surface of its starting plastic strain,
//   and the residual edge past the softening strain;
// - objectivity: a rigid rotation applied to a plastically stressed point
//   rotates its stress, keeps the invariants and the plastic strain.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/hencky_plasticity.h>

#include <cmath>
#include <random>

#include "tests.h"

using namespace dealii;
using namespace mpm;

const double E = 1e7, nu = 0.3;
const double lambda_ = E * nu / ((1 + nu) * (1 - 2 * nu));
const double mu_     = E / (2 * (1 + nu));

std::unique_ptr<HenckyPlasticity>
make(const std::string &                                    model,
     const std::vector<std::pair<std::string, std::string>> &settings)
{
  ParameterHandler prm;
  Material::declare_parameters(prm);
  prm.set("Model", model);
  prm.set("Young's modulus", std::to_string(E));
  prm.set("Poisson's ratio", std::to_string(nu));
  prm.enter_subsection(model);
  for (const auto &[entry, value] : settings)
    prm.set(entry, value);
  prm.leave_subsection();
  auto material = Material::create(prm, "test", "test");
  return std::unique_ptr<HenckyPlasticity>(
    dynamic_cast<HenckyPlasticity *>(material.release()));
}

Tensor<2, 3>
rotation(const double a, const double b, const double c)
{
  Tensor<2, 3> Rz, Ry, Rx;
  Rz[0][0] = Rz[1][1] = std::cos(a);
  Rz[0][1]            = -std::sin(a);
  Rz[1][0]            = std::sin(a);
  Rz[2][2]            = 1.;
  Ry[0][0] = Ry[2][2] = std::cos(b);
  Ry[0][2]            = std::sin(b);
  Ry[2][0]            = -std::sin(b);
  Ry[1][1]            = 1.;
  Rx[1][1] = Rx[2][2] = std::cos(c);
  Rx[1][2]            = -std::sin(c);
  Rx[2][1]            = std::sin(c);
  Rx[0][0]            = 1.;
  return Rz * Ry * Rx;
}

Tensor<2, 3>
diagonal(const double a, const double b, const double c)
{
  Tensor<2, 3> F;
  F[0][0] = a;
  F[1][1] = b;
  F[2][2] = c;
  return F;
}

/** One step from F_old to F_new, updating stress and internal state. */
struct State
{
  Tensor<2, 3>          F = unit_symmetric_tensor<3>();
  SymmetricTensor<2, 3> stress;
  std::vector<double>   internal = std::vector<double>(7, 0.);

  StepKinematics
  kinematics(const Tensor<2, 3> &F_new) const
  {
    StepKinematics k;
    k.F_old             = F;
    k.F_new             = F_new;
    k.dt                = 1.;
    k.velocity_gradient = F_new * invert(F) - Tensor<2, 3>(unit_symmetric_tensor<3>());
    return k;
  }

  void
  step(const Material &material, const Tensor<2, 3> &F_new)
  {
    material.update_stress(kinematics(F_new),
                           stress,
                           ArrayView<double>(internal.data(), internal.size()));
    F = F_new;
  }
};

/** Principal Kirchhoff stresses of a state. */
Tensor<1, 3>
principal_tau(const State &state)
{
  // Jacobi: the closed-form eigenvalues lose half the digits at the
  // repeated stresses of the edges and the apex.
  const auto   eigen =
    eigenvectors(state.stress, SymmetricTensorEigenvectorMethod::jacobi);
  const double J = determinant(state.F);
  return Tensor<1, 3>(
    {J * eigen[0].first, J * eigen[1].first, J * eigen[2].first});
}

/** Largest relative difference of the closed-form and numerical tangents. */
double
tangent_error(const HenckyPlasticity &material,
              const State &           state,
              const Tensor<2, 3> &    F_new)
{
  const StepKinematics          k = state.kinematics(F_new);
  const ArrayView<const double> internal(state.internal.data(),
                                         state.internal.size());
  const SymmetricTensor<4, 3>   exact =
    material.spatial_tangent(k, state.stress, internal);
  const SymmetricTensor<4, 3> numerical =
    material.numerical_spatial_tangent(k, state.stress, internal);
  return (exact - numerical).norm() / (lambda_ + 2 * mu_);
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  const double c = 5e4, phi = 30., psi = 10.;
  const double sin_phi = std::sin(phi * numbers::PI / 180.);
  const double k       = (1 + sin_phi) / (1 - sin_phi);
  const double sin_psi = std::sin(psi * numbers::PI / 180.);
  const double m       = (1 + sin_psi) / (1 - sin_psi);
  const double sigma_c = 2 * c * std::sqrt(k);

  const auto mohr_coulomb = make("Mohr-Coulomb",
                                 {{"Cohesion", "5e4"},
                                  {"Friction angle", "30"},
                                  {"Dilatancy angle", "10"}});
  const auto associated   = make("Mohr-Coulomb",
                               {{"Cohesion", "5e4"},
                                {"Friction angle", "25"},
                                {"Dilatancy angle", "25"}});
  // Softening to c_r = 1e4, phi_r = 20 at plastic strain 0.01.
  const double c_r = 1e4;
  const double sin_phi_r = std::sin(20. * numbers::PI / 180.);
  const double k_r       = (1 + sin_phi_r) / (1 - sin_phi_r);
  const auto   softening = make("Mohr-Coulomb",
                              {{"Cohesion", "5e4"},
                               {"Friction angle", "30"},
                               {"Dilatancy angle", "10"},
                               {"Softening plastic strain", "0.01"},
                               {"Residual cohesion", "1e4"},
                               {"Residual friction angle", "20"}});
  // Tension cut-off t = 2e4, below the apex c cot(phi) = 8.7e4.
  const double t         = 2e4;
  const auto   cut_off   = make("Mohr-Coulomb",
                            {{"Cohesion", "5e4"},
                             {"Friction angle", "30"},
                             {"Dilatancy angle", "10"},
                             {"Tension cut-off", "true"},
                             {"Tensile strength", "2e4"}});
  const double sigma_y = 2.05e5, H = 1e6;
  const auto   perfect   = make("von Mises", {{"Yield stress", "2.05e5"}});
  const auto   hardening = make("von Mises",
                              {{"Yield stress", "2.05e5"},
                               {"Hardening modulus", "1e6"}});

  // Random returns.
  {
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> angle(0., numbers::PI);
    std::uniform_real_distribution<double> stretch(-0.03, 0.03);
    const std::vector<std::pair<std::string, const HenckyPlasticity *>> laws =
      {{"Mohr-Coulomb phi 30 psi 10", mohr_coulomb.get()},
       {"Mohr-Coulomb associated", associated.get()},
       {"Mohr-Coulomb softening", softening.get()},
       {"Mohr-Coulomb tension cut-off", cut_off.get()},
       {"von Mises perfect", perfect.get()},
       {"von Mises hardening", hardening.get()}};
    for (const auto &[name, law] : laws)
      {
        const bool   mohr = name.find("Mohr") != std::string::npos;
        double       worst   = 0.;
        unsigned int plane = 0, edge = 0, apex = 0, tension = 0,
                     tension_corner = 0, edge_12 = 0, edge_23 = 0;
        for (unsigned int sample = 0; sample < 750; ++sample)
          {
            State  state;
            double start_plastic_strain = 0.;
            // An earlier step, then the one checked; a hydrostatic part
            // biased to tension reaches the apex.
            for (unsigned int s = 0; s < 2; ++s)
              {
                const double       bias = (sample % 3 == 0) ? 0.02 : 0.;
                const Tensor<2, 3> R =
                  rotation(angle(random), angle(random), angle(random));
                const Tensor<2, 3> U =
                  diagonal(std::exp(stretch(random) + bias),
                           std::exp(stretch(random) + bias),
                           std::exp(stretch(random) + bias));
                start_plastic_strain = state.internal[0];
                state.step(*law, R * U * transpose(R) * state.F);
              }
            // Softening is explicit: a step returns to the surface of the
            // plastic strain at its start; hardening (von Mises) is
            // implicit, to the surface of its end.
            const Tensor<1, 3> tau = principal_tau(state);
            const double       f   = law->yield_function(
              tau, mohr ? start_plastic_strain : state.internal[0]);
            worst = std::max(worst, f / (sigma_c + sigma_y));
            // Which return: the apex has three equal stresses, an edge two
            // (tau is in descending order: tau_1 = tau_2 or tau_2 = tau_3).
            const double scale = tau.norm() * 1e-9 + 1.;
            const bool   e01   = std::abs(tau[0] - tau[1]) < scale;
            const bool   e12   = std::abs(tau[1] - tau[2]) < scale;
            const bool   e02   = std::abs(tau[0] - tau[2]) < scale;
            if (std::abs(f) < 1e-6 * sigma_c)
              {
                const double largest = std::max({tau[0], tau[1], tau[2]});
                if (law == cut_off.get() && std::abs(largest - t) < scale)
                  {
                    ++tension;
                    if (e01 && e12)
                      ++tension_corner;
                  }
                else if (e01 && e12)
                  ++apex;
                else if (e01 || e12 || e02)
                  {
                    ++edge;
                    edge_12 += e01;
                    edge_23 += e12;
                  }
                else
                  ++plane;
              }
          }
        mpm_tests::check(name + ": every return on or inside the yield "
                                "surface to 1e-10",
                         worst < 1e-10);
        if (law == cut_off.get())
          mpm_tests::check(name + ": returns to the Mohr-Coulomb planes and "
                                  "edges, to the cut-off and to its corner "
                                  "(at least 10 each)",
                           plane >= 10 && edge >= 10 && tension >= 10 &&
                             tension_corner >= 10);
        else if (mohr)
          mpm_tests::check(name + ": returns to the plane, both edges "
                                  "(tau_1 = tau_2 and tau_2 = tau_3) and the "
                                  "apex (at least 10 each)",
                           plane >= 10 && edge_12 >= 10 && edge_23 >= 10 &&
                             apex >= 10);
      }
  }

  // Consistent tangent against differences of the update.
  {
    struct Case
    {
      std::string             name;
      const HenckyPlasticity *law;
      Tensor<2, 3>            F;
    };
    const Tensor<2, 3> R = rotation(0.3, 0.5, 0.7);
    auto rotated = [&](const Tensor<2, 3> &U) { return R * U * transpose(R); };
    const std::vector<Case> cases = {
      {"Mohr-Coulomb elastic", mohr_coulomb.get(),
       rotated(diagonal(1.001, 0.9995, 1.0002))},
      {"Mohr-Coulomb plane", mohr_coulomb.get(),
       rotated(diagonal(1.02, 0.995, 0.98))},
      {"Mohr-Coulomb edge tau_1 = tau_2", mohr_coulomb.get(),
       rotated(diagonal(1.0, 1.0, 0.97))},
      {"Mohr-Coulomb edge tau_2 = tau_3", mohr_coulomb.get(),
       rotated(diagonal(1.02, 0.98, 0.98))},
      {"Mohr-Coulomb apex", mohr_coulomb.get(),
       rotated(diagonal(1.02, 1.02, 1.02))},
      {"Mohr-Coulomb softening plane", softening.get(),
       rotated(diagonal(1.02, 0.995, 0.98))},
      {"Mohr-Coulomb softening edge tau_1 = tau_2", softening.get(),
       rotated(diagonal(1.0, 1.0, 0.97))},
      {"Cut-off plane (after a plastic step: its line with Mohr-Coulomb)",
       cut_off.get(), rotated(diagonal(1.004, 1.0005, 0.9998))},
      {"Cut-off edge tau_1 = tau_2 = t", cut_off.get(),
       rotated(diagonal(1.006, 1.006, 0.995))},
      {"Cut-off corner", cut_off.get(),
       rotated(diagonal(1.011, 1.01, 1.012))},
      {"von Mises elastic", hardening.get(),
       rotated(diagonal(1.001, 0.9995, 1.0))},
      {"von Mises plastic", hardening.get(),
       rotated(diagonal(1.05, 0.98, 0.99))},
      {"von Mises, equal stretches", perfect.get(),
       rotated(diagonal(1.05, 0.99, 0.99))}};
    for (const auto &test : cases)
      {
        State        fresh;
        const double error = tangent_error(*test.law, fresh, test.F);
        mpm_tests::check(test.name + ": consistent tangent = differences to "
                                     "1e-6",
                         error < 1e-6);
        // The same after an earlier plastic step and a rotation.
        State earlier;
        earlier.step(*test.law, rotated(diagonal(1.03, 0.99, 0.985)));
        const Tensor<2, 3> Q = rotation(0.2, -0.4, 0.1);
        const double error_after =
          tangent_error(*test.law, earlier, Q * test.F * earlier.F);
        mpm_tests::check(test.name + ", after a plastic step: consistent "
                                     "tangent = differences to 1e-6",
                         error_after < 1e-6);
      }
  }

  // von Mises in uniaxial and biaxial strain.
  {
    const double K = lambda_ + 2. / 3. * mu_;
    for (const auto &[law, h] : {std::make_pair(perfect.get(), 0.),
                                 std::make_pair(hardening.get(), H)})
      {
        State        state;
        double       yield_at = 0., error = 0., flow_error = 0.;
        const double eps_y    = sigma_y / (2 * mu_);
        unsigned int n_plastic = 0;
        for (unsigned int n = 1; n <= 500; ++n)
          {
            const double eps = 1e-4 * n;
            state.step(*law, diagonal(std::exp(eps), 1., 1.));
            const double tau_xx = determinant(state.F) * state.stress[0][0];
            const double tau_yy = determinant(state.F) * state.stress[1][1];
            const double eps_p = state.internal[0];
            if (eps_p > 0. && yield_at == 0.)
              yield_at = eps;
            // Mean stress elastic throughout.
            error = std::max(error,
                             std::abs((tau_xx + 2 * tau_yy) / 3 - K * eps) /
                               sigma_y);
            if (eps > eps_y)
              {
                ++n_plastic;
                error = std::max(error,
                                 std::abs(tau_xx - tau_yy - sigma_y - h * eps_p) /
                                   sigma_y);
                // Plastic strain = total - elastic, along (2, -1, -1).
                const double ee_xx = (tau_xx - lambda_ / (3 * lambda_ + 2 * mu_) *
                                                 (tau_xx + 2 * tau_yy)) /
                                     (2 * mu_);
                const double ee_yy = (tau_yy - lambda_ / (3 * lambda_ + 2 * mu_) *
                                                 (tau_xx + 2 * tau_yy)) /
                                     (2 * mu_);
                const double ep_xx = eps - ee_xx, ep_yy = -ee_yy;
                flow_error = std::max(flow_error,
                                      std::abs(ep_xx + 2 * ep_yy) / eps_y);
              }
          }
        const std::string name = h > 0 ? "hardening" : "perfect";
        mpm_tests::check("von Mises " + name + ", uniaxial strain: yields in "
                         "the step that crosses sigma_y / (2 mu)",
                         yield_at >= eps_y && yield_at < eps_y + 1e-4);
        mpm_tests::check("von Mises " + name + ", uniaxial strain: tau_xx - "
                         "tau_yy = sigma_y + H eps_p, mean stress K eps, "
                         "to 1e-9, over 220 plastic steps",
                         error < 1e-9 && n_plastic > 220);
        mpm_tests::check("von Mises " + name + ", uniaxial strain: plastic "
                         "strain along (2, -1, -1) to 1e-9",
                         flow_error < 1e-9);
      }
    State        state;
    double       error     = 0.;
    unsigned int n_plastic = 0;
    for (unsigned int n = 1; n <= 300; ++n)
      {
        const double e = 2e-4 * n;
        state.step(*perfect, diagonal(std::exp(e), std::exp(e), 1.));
        const double J = determinant(state.F);
        if (2 * mu_ * e > sigma_y * 1.001 && ++n_plastic)
          error = std::max(error,
                           std::abs(J * (state.stress[0][0] - state.stress[2][2]) -
                                    sigma_y) /
                             sigma_y);
      }
    mpm_tests::check("von Mises, biaxial strain: tau_xx - tau_zz = sigma_y "
                     "after yield, to 1e-9, over 160 plastic steps",
                     error < 1e-9 && n_plastic > 160);
  }

  // Mohr-Coulomb in compression with the lateral strain of uniaxial stress,
  // (nu e, nu e, -e): tau_x = tau_y = 0 while elastic (exact for Hencky),
  // so it yields at the unconfined strength, E e = 2 c sqrt(k).
  {
    const double e_y = sigma_c / E;
    unsigned int n_plastic = 0;
    State        state;
    double       yield_at = 0., error = 0., flow_error = 0.;
    double       last_ep_x = 0., last_ep_z = 0.;
    for (unsigned int n = 1; n <= 400; ++n)
      {
        const double e = 1e-4 * n;
        state.step(*mohr_coulomb,
                   diagonal(std::exp(nu * e), std::exp(nu * e), std::exp(-e)));
        const double J     = determinant(state.F);
        const double tau_x = J * state.stress[0][0];
        const double tau_y = J * state.stress[1][1];
        const double tau_z = J * state.stress[2][2];
        if (state.internal[0] > 0. && yield_at == 0.)
          yield_at = e;
        if (e > e_y * 1.001)
          {
            ++n_plastic;
            error = std::max({error,
                              std::abs(k * tau_x - tau_z - sigma_c) / sigma_c,
                              std::abs(tau_x - tau_y) / sigma_c});
            // Plastic strain: total (nu e, nu e, -e) minus elastic D^-1 tau.
            const double trace = tau_x + tau_y + tau_z;
            const double scale = lambda_ / (3 * lambda_ + 2 * mu_);
            const double ep_x  = nu * e - (tau_x - scale * trace) / (2 * mu_);
            const double ep_z  = -e - (tau_z - scale * trace) / (2 * mu_);
            if (last_ep_z != 0.)
              {
                // Increment ratio d eps_p,x / d eps_p,z = -m / 2.
                const double ratio = (ep_x - last_ep_x) / (ep_z - last_ep_z);
                flow_error = std::max(flow_error, std::abs(ratio + m / 2));
              }
            last_ep_x = ep_x;
            last_ep_z = ep_z;
          }
      }
    mpm_tests::check("Mohr-Coulomb triaxial compression: yields in the step "
                     "that crosses E e = 2 c sqrt(k)",
                     yield_at >= e_y && yield_at < e_y + 1e-4);
    mpm_tests::check("Mohr-Coulomb triaxial compression: on the edge k "
                     "tau_x - tau_z = 2 c sqrt(k), tau_x = tau_y, to 1e-9, "
                     "over 200 plastic steps",
                     error < 1e-9 && n_plastic > 200);
    mpm_tests::check("Mohr-Coulomb triaxial compression: plastic flow "
                     "(m, m, -2) to 1e-8",
                     flow_error < 1e-8);
  }

  // Mohr-Coulomb apex.
  {
    State state;
    state.step(*mohr_coulomb, diagonal(1.05, 1.05, 1.05));
    const double apex = sigma_c / (k - 1.);
    const double J    = determinant(state.F);
    double       error = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        error = std::max(error,
                         std::abs(J * state.stress[i][j] -
                                  (i == j ? apex : 0.)) /
                           apex);
    mpm_tests::check("Mohr-Coulomb hydrostatic tension: tau = c cot(phi) "
                     "at the apex to 1e-12",
                     error < 1e-12);
  }

  // Tension cut-off in uniaxial strain (exp(e), 1, 1): tau_x = (lambda +
  // 2 mu) e reaches t; then the cut-off alone is active and its flow
  // (1, 0, 0) keeps tau_x = t and holds tau_y = tau_z = lambda t /
  // (lambda + 2 mu), wherever e goes.
  {
    State        state;
    double       yield_at = 0., error = 0.;
    unsigned int n_plastic = 0;
    const double e_t       = t / (lambda_ + 2 * mu_);
    for (unsigned int n = 1; n <= 200; ++n)
      {
        const double e = 2e-5 * n;
        state.step(*cut_off, diagonal(std::exp(e), 1., 1.));
        if (state.internal[0] > 0. && yield_at == 0.)
          yield_at = e;
        if (e > e_t)
          {
            ++n_plastic;
            const double J      = determinant(state.F);
            const double expected_yy = lambda_ * t / (lambda_ + 2 * mu_);
            error = std::max({error,
                              std::abs(J * state.stress[0][0] - t) / t,
                              std::abs(J * state.stress[1][1] - expected_yy) / t,
                              std::abs(J * state.stress[2][2] - expected_yy) / t});
          }
      }
    mpm_tests::check("Tension cut-off, uniaxial strain: yields in the step "
                     "that crosses (lambda + 2 mu) e = t",
                     yield_at >= e_t && yield_at < e_t + 2e-5);
    mpm_tests::check("Tension cut-off, uniaxial strain: tau_xx = t, tau_yy = "
                     "tau_zz = lambda t / (lambda + 2 mu) to 1e-9, over 100 "
                     "plastic steps",
                     error < 1e-9 && n_plastic > 100);
  }

  // Softening in the compression path above: each step ends on the edge of
  // the surface at the plastic strain of its start (explicit softening),
  // and beyond the softening strain the edge is that of
  // c_r and phi_r: k_r tau_x - tau_z = 2 c_r sqrt(k_r).
  {
    State        state;
    double       edge_error = 0., residual_error = 0.;
    unsigned int n_residual = 0;
    for (unsigned int n = 1; n <= 600; ++n)
      {
        const double e          = 1e-4 * n;
        const double start_eps_p = state.internal[0];
        state.step(*softening,
                   diagonal(std::exp(nu * e), std::exp(nu * e), std::exp(-e)));
        if (state.internal[0] == 0.)
          continue;
        const Tensor<1, 3> tau = principal_tau(state);
        edge_error = std::max(edge_error,
                              std::abs(softening->yield_function(tau,
                                                                 start_eps_p)) /
                                sigma_c);
        const double J = determinant(state.F);
        if (start_eps_p > 0.01)
          {
            ++n_residual;
            const double tau_x = J * state.stress[0][0];
            const double tau_z = J * state.stress[2][2];
            residual_error =
              std::max(residual_error,
                       std::abs(k_r * tau_x - tau_z - 2 * c_r * std::sqrt(k_r)) /
                         sigma_c);
          }
      }
    mpm_tests::check("Mohr-Coulomb softening: every plastic step on the "
                     "surface of its starting plastic strain to 1e-9",
                     edge_error < 1e-9);
    mpm_tests::check("Mohr-Coulomb softening: past the softening strain on "
                     "the residual edge k_r tau_x - tau_z = 2 c_r sqrt(k_r) "
                     "to 1e-9, over 50 steps",
                     residual_error < 1e-9 && n_residual > 50);
  }

  // Objectivity of a plastic state.
  for (const auto *law : {mohr_coulomb.get(), hardening.get()})
    {
      State state;
      state.step(*law, rotation(0.1, 0.2, 0.3) * diagonal(1.03, 0.99, 0.975));
      const double eps_p = state.internal[0];
      const auto   before = eigenvalues(state.stress);
      const Tensor<2, 3> R = rotation(0.9, -0.6, 0.4);
      const SymmetricTensor<2, 3> expected =
        symmetrize(Tensor<2, 3>(R * Tensor<2, 3>(state.stress) * transpose(R)));
      state.step(*law, R * state.F);
      const auto after = eigenvalues(state.stress);
      double     error = (state.stress - expected).norm();
      for (unsigned int i = 0; i < 3; ++i)
        error = std::max(error, std::abs(after[i] - before[i]));
      mpm_tests::check(std::string(law == mohr_coulomb.get() ? "Mohr-Coulomb" :
                                                             "von Mises") +
                         ": a rigid rotation rotates the stress and keeps "
                         "invariants and plastic strain, to 1e-9",
                       error < 1e-9 * sigma_c &&
                         std::abs(state.internal[0] - eps_p) < 1e-14);
    }
}
