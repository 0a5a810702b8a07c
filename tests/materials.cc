// The constitutive laws against closed forms:
// - neo-Hookean in uniaxial strain with nu = 0: sigma_xx = E sinh(eps_L)
//   (benchmarks.md section 4), for stretch and compression;
// - neo-Hookean: a rigid rotation of a stretched state rotates the stress
//   (sigma = R sigma_0 R^T) and leaves its invariants;
// - Hencky in uniaxial strain with nu = 0: sigma_xx = E eps_L / exp(eps_L)
//   (the Kirchhoff stress is E eps_L; benchmarks.md section 4), and
//   objectivity;
// - linear elastic (Jaumann) in small uniaxial strain: Hooke's law,
//   sigma_xx = (lambda + 2 mu) eps, sigma_yy = sigma_zz = lambda eps;
// - linear elastic (Jaumann) in uniaxial strain at a constant velocity
//   gradient D_xx: sigma_xx = (lambda + 2 mu) eps_L with eps_L = D_xx t, the
//   closed form of a hypoelastic law with constant stiffness;
// - linear elastic (Jaumann): a pure spin applied to a stressed point
//   rotates the stress and keeps its invariants.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/material.h>

#include <cmath>

#include "tests.h"

using namespace dealii;
using namespace mpm;

std::unique_ptr<Material>
make(const std::string &model, const double E, const double nu)
{
  ParameterHandler prm;
  Material::declare_parameters(prm);
  prm.set("Model", model);
  prm.set("Young's modulus", std::to_string(E));
  prm.set("Poisson's ratio", std::to_string(nu));
  return Material::create(prm, "test", "test");
}

Tensor<2, 3>
rotation_z(const double angle)
{
  Tensor<2, 3> R;
  R[0][0] = R[1][1] = std::cos(angle);
  R[0][1]           = -std::sin(angle);
  R[1][0]           = std::sin(angle);
  R[2][2]           = 1.;
  return R;
}

/**
 * A hyperelastic law in uniaxial strain (nu = 0) against its closed form
 * sigma_xx / E = closed_form(eps_L), and under a rigid rotation.
 */
template <typename ClosedForm>
void
hyperelastic(const std::string &model,
             const std::string &formula,
             const ClosedForm & closed_form)
{
  const double E        = 1e6;
  const auto   material = make(model, E, 0.);
  double       error    = 0.;
  for (const double eps_L : {-0.5, -0.2, 0.1, 0.28, 0.5})
    {
      StepKinematics k;
      k.F_old       = unit_symmetric_tensor<3>();
      k.F_new       = unit_symmetric_tensor<3>();
      k.F_new[0][0] = std::exp(eps_L);
      k.dt          = 1.;
      SymmetricTensor<2, 3> stress;
      material->update_stress(k, stress, {});
      error = std::max(error, std::abs(stress[0][0] / E - closed_form(eps_L)));
      error = std::max({error, std::abs(stress[1][1]), std::abs(stress[2][2])});
    }
  mpm_tests::check(model + " uniaxial strain: sigma = " + formula +
                     " to 1e-12 E",
                   error < 1e-12 * E);

  // Rotate a stretched state rigidly.
  const auto     material3 = make(model, E, 0.3);
  StepKinematics k;
  k.F_old       = unit_symmetric_tensor<3>();
  k.F_new       = unit_symmetric_tensor<3>();
  k.F_new[0][0] = 1.2;
  k.F_new[1][1] = 0.9;
  k.F_new[0][1] = 0.1;
  k.dt          = 1.;
  SymmetricTensor<2, 3> s0, s1;
  material3->update_stress(k, s0, {});
  const Tensor<2, 3> R = rotation_z(0.7);
  k.F_new              = R * k.F_new;
  material3->update_stress(k, s1, {});
  const Tensor<2, 3> expected = R * Tensor<2, 3>(s0) * transpose(R);
  mpm_tests::check(model + " is objective: sigma(R F) = R sigma(F) R^T",
                   (Tensor<2, 3>(s1) - expected).norm() < 1e-9 * s0.norm());
}

void
linear_elastic()
{
  const double E = 1e6, nu = 0.3;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu     = E / (2 * (1 + nu));
  const auto   material = make("linear elastic", E, nu);

  // One small step: Hooke's law.
  {
    StepKinematics k;
    k.dt                      = 1.;
    k.velocity_gradient[0][0] = 1e-6;
    SymmetricTensor<2, 3> stress;
    material->update_stress(k, stress, {});
    mpm_tests::check("Jaumann elastic, small strain: Hooke's law",
                     std::abs(stress[0][0] - (lambda + 2 * mu) * 1e-6) <
                         1e-12 * E &&
                       std::abs(stress[1][1] - lambda * 1e-6) < 1e-12 * E &&
                       std::abs(stress[2][2] - lambda * 1e-6) < 1e-12 * E);
  }

  // Many steps of constant log strain rate to eps_L = 0.3.
  {
    const unsigned int    n = 1000;
    const double          eps_L = 0.3;
    StepKinematics        k;
    k.dt                      = 1. / n;
    k.velocity_gradient[0][0] = eps_L;
    SymmetricTensor<2, 3> stress;
    for (unsigned int i = 0; i < n; ++i)
      material->update_stress(k, stress, {});
    mpm_tests::check("Jaumann elastic, uniaxial strain: sigma_xx = (lambda + "
                     "2 mu) eps_L",
                     std::abs(stress[0][0] - (lambda + 2 * mu) * eps_L) <
                       1e-12 * E);
  }

  // A pure spin rotates a uniaxial stress state: after rotating by angle
  // theta the stress is R sigma R^T to first order in the step.
  {
    SymmetricTensor<2, 3> stress;
    stress[0][0]              = 1e5;
    const double       omega  = 1.;
    const unsigned int n      = 100000;
    StepKinematics     k;
    k.dt                      = 1. / n;
    k.velocity_gradient[0][1] = -omega;
    k.velocity_gradient[1][0] = omega;
    const double I1 = trace(stress), I2 = second_invariant(stress);
    for (unsigned int i = 0; i < n; ++i)
      material->update_stress(k, stress, {});
    const Tensor<2, 3> R = rotation_z(omega);
    SymmetricTensor<2, 3> start;
    start[0][0] = 1e5;
    const Tensor<2, 3> expected = R * Tensor<2, 3>(start) * transpose(R);
    mpm_tests::check("Jaumann elastic, pure spin: invariants kept to 1e-4",
                     std::abs(trace(stress) - I1) < 1e-4 * 1e5 &&
                       std::abs(second_invariant(stress) - I2) <
                         1e-4 * 1e10);
    mpm_tests::check("Jaumann elastic, pure spin: sigma rotates with the "
                     "material to 1e-4",
                     (Tensor<2, 3>(stress) - expected).norm() < 1e-4 * 1e5);
  }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  hyperelastic("neo-Hookean", "E sinh(eps_L)", [](const double eps) {
    return std::sinh(eps);
  });
  hyperelastic("Hencky", "E eps_L / exp(eps_L)", [](const double eps) {
    return eps / std::exp(eps);
  });
  linear_elastic();
}
