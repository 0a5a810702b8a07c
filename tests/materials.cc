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
// - the closed-form principal axes of the 2D scenes' tensors (t_xz = t_yz
//   = 0) against deal.II's Jacobi rotations, with equal and nearly equal
//   eigenvalues (planted: a sign error in the first axis fails it).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/material.h>
#include <mpm/materials/principal_axes.h>

#include <cmath>
#include <random>

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

/**
 * The closed-form principal axes of a tensor with t_xz = t_yz = 0 (the 2D
 * scenes' finite-strain laws use them) against deal.II's Jacobi rotations:
 * random tensors, stretch-like (near I, as b of a small step) and
 * stress-like (any sign), equal and nearly equal in-plane eigenvalues, and
 * t_zz above, between and below them. The eigenvalues must agree, largest
 * first, and sum lambda v v^T must give back t; a tensor with t_xz != 0
 * goes to Jacobi itself.
 */
void
principal_axes_of_plane_tensors()
{
  std::mt19937                           random(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  std::vector<SymmetricTensor<2, 3>>     cases;
  for (unsigned int k = 0; k < 2000; ++k)
    {
      SymmetricTensor<2, 3> t;
      const double          size = k % 2 ? 1e5 : 0.05;
      t[0][0] = (k % 2 ? 0. : 1.) + size * uniform(random);
      t[1][1] = (k % 2 ? 0. : 1.) + size * uniform(random);
      t[0][1] = size * uniform(random);
      t[2][2] = (k % 2 ? 0. : 1.) + size * uniform(random);
      cases.push_back(t);
    }
  for (const double gap : {0., 1e-14, 1e-9})
    for (const double zz : {2., 1., 0.5})
      {
        SymmetricTensor<2, 3> t;
        t[0][0] = 1.;
        t[1][1] = 1. + gap;
        t[2][2] = zz;
        cases.push_back(t);
      }
  double value_gap = 0., rebuild_gap = 0.;
  bool   ordered   = true;
  for (const auto &t : cases)
    {
      const auto axes  = mpm::principal_axes(t);
      const auto jacobi = eigenvectors(t, SymmetricTensorEigenvectorMethod::jacobi);
      SymmetricTensor<2, 3> rebuilt;
      for (unsigned int a = 0; a < 3; ++a)
        {
          value_gap = std::max(value_gap,
                               std::abs(axes[a].first - jacobi[a].first) /
                                 t.norm());
          rebuilt += axes[a].first *
                     symmetrize(outer_product(axes[a].second, axes[a].second));
        }
      rebuild_gap = std::max(rebuild_gap, (rebuilt - t).norm() / t.norm());
      ordered = ordered && axes[0].first >= axes[1].first &&
                axes[1].first >= axes[2].first;
    }
  mpm_tests::check("principal axes in closed form (t_xz = t_yz = 0): the "
                   "eigenvalues of Jacobi's rotations to 1e-14, largest "
                   "first, and sum lambda v v^T = t to 1e-14",
                   value_gap < 1e-14 && rebuild_gap < 1e-14 && ordered);

  SymmetricTensor<2, 3> general = cases[0];
  general[0][2]                 = 0.01;
  const auto axes               = mpm::principal_axes(general);
  SymmetricTensor<2, 3> rebuilt;
  for (unsigned int a = 0; a < 3; ++a)
    rebuilt +=
      axes[a].first * symmetrize(outer_product(axes[a].second, axes[a].second));
  mpm_tests::check("a tensor with t_xz != 0 is decomposed too (1e-14)",
                   (rebuilt - general).norm() < 1e-14 * general.norm());
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
  principal_axes_of_plane_tensors();
}
