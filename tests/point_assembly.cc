// The updated-Lagrangian point assembly that the implicit schemes share:
// the tangent (material + geometric stiffness) must be the derivative of the
// internal force with respect to the nodal displacement increments. Checked
// against central differences at random pre-deformed states on a distorted
// cell, for the neo-Hookean law (analytical tangent) and the Hencky law
// (tangent by central differences of the stress), in 2D and 3D;
// and the internal forces of a point sum to zero (equilibrium of a single
// integration point under a constant stress). In 2D also as a ring of an
// axisymmetric scene, at radius 0.4 with a hoop stretch of 1.1 already:
// the hoop stretch of the step is 1 + u_r / r and the hoop terms join the
// force and the tangent, which must still be its derivative (and, for
// these hyperelastic laws, symmetric); the axial forces sum to zero, the
// radial ones to the hoop force.

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <mpm/assembly/point_assembly.h>
#include <mpm/materials/material.h>
#include <mpm/points/point_layout.h>

#include <random>

#include "tests.h"

using namespace dealii;
using namespace mpm;

template <int dim>
void
test(const std::string &model, const bool axisymmetric = false)
{
  deallog << "dim = " << dim << ", " << model
          << (axisymmetric ? ", axisymmetric" : "") << std::endl;
  ParameterHandler prm;
  Material::declare_parameters(prm);
  prm.set("Model", model);
  prm.set("Young's modulus", "1e6");
  prm.set("Poisson's ratio", "0.3");
  const auto material = Material::create(prm, model, model);

  std::mt19937                           rng(7);
  std::uniform_real_distribution<double> uniform(-1., 1.);

  // A support with gradients of a distorted Q1 cell: shape functions of the
  // unit cell mapped by a random affine map plus the Q1 structure.
  Support<dim> support;
  support.resize(1u << dim);
  Tensor<2, dim> map = unit_symmetric_tensor<dim>();
  for (unsigned int a = 0; a < dim; ++a)
    for (unsigned int b = 0; b < dim; ++b)
      map[a][b] += 0.2 * uniform(rng);
  const Tensor<2, dim> map_inverse_transpose = transpose(invert(map));
  Point<dim>           xi;
  for (unsigned int d = 0; d < dim; ++d)
    xi[d] = 0.5 + 0.4 * uniform(rng);
  for (unsigned int v = 0; v < support.n_nodes; ++v)
    {
      Tensor<1, dim> grad;
      double         value = 1.;
      for (unsigned int d = 0; d < dim; ++d)
        value *= (v & (1u << d)) ? xi[d] : 1. - xi[d];
      for (unsigned int k = 0; k < dim; ++k)
        {
          double g = (v & (1u << k)) ? 1. : -1.;
          for (unsigned int d = 0; d < dim; ++d)
            if (d != k)
              g *= (v & (1u << d)) ? xi[d] : 1. - xi[d];
          grad[k] = g;
        }
      support.N[v]      = value;
      support.grad_N[v] = map_inverse_transpose * grad;
      support.nodes[v]  = v;
    }

  // A pre-deformed state F_n and a random displacement increment.
  Tensor<2, dim> F_n = unit_symmetric_tensor<dim>();
  for (unsigned int a = 0; a < dim; ++a)
    for (unsigned int b = 0; b < dim; ++b)
      F_n[a][b] += 0.15 * uniform(rng);
  std::vector<Tensor<1, dim>> du(support.n_nodes);
  for (auto &u : du)
    for (unsigned int d = 0; d < dim; ++d)
      u[d] = 0.05 * uniform(rng);
  const double V0 = 0.3;
  // The ring's radius at the start of the step, and its hoop stretch then.
  const double radius       = 0.4;
  const double hoop_stretch = axisymmetric ? 1.1 : 1.;

  // Internal force and, optionally, tangent at a displacement increment;
  // also a ring's hoop force v sigma_tt / r, if asked.
  auto evaluate = [&](const std::vector<Tensor<1, dim>> &u,
                      Vector<double> &                   force,
                      FullMatrix<double> *               tangent,
                      double *hoop_force = nullptr) {
    const Tensor<2, dim> dF =
      PointAssembly<dim>::deformation_increment(support, u);
    double u_r = 0.;
    for (unsigned int i = 0; i < support.n_nodes; ++i)
      u_r += support.N[i] * u[i][0];
    const double   hoop = axisymmetric ? 1. + u_r / radius : 1.;
    StepKinematics k;
    k.F_old = PointLayout<dim>::embed(F_n, hoop_stretch);
    k.F_new = PointLayout<dim>::embed(dF * F_n, hoop_stretch * hoop);
    k.dt    = 1.;
    const SymmetricTensor<2, 3> old_stress;
    SymmetricTensor<2, 3>       stress = old_stress;
    material->update_stress(k, stress, {});
    const SymmetricTensor<4, 3> c =
      material->spatial_tangent(k, old_stress, {});
    typename PointAssembly<dim>::Scratch scratch;
    PointAssembly<dim>::internal_force(support,
                                       &dF,
                                       determinant(k.F_new) * V0,
                                       stress,
                                       &c,
                                       tangent,
                                       scratch,
                                       axisymmetric ? radius * hoop : 0.);
    force = Vector<double>(scratch.force.begin(), scratch.force.end());
    if (hoop_force != nullptr)
      *hoop_force = axisymmetric ? determinant(k.F_new) * V0 * stress[2][2] /
                                     (radius * hoop) :
                                   0.;
  };

  Vector<double>     force;
  FullMatrix<double> tangent;
  // A ring's radial forces sum to its hoop force.
  double hoop_force;
  evaluate(du, force, &tangent, &hoop_force);

  double equilibrium = 0.;
  for (unsigned int a = 0; a < dim; ++a)
    {
      double sum = a == 0 ? -hoop_force : 0.;
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        sum += force(i * dim + a);
      equilibrium = std::max(equilibrium, std::abs(sum));
    }
  mpm_tests::check(axisymmetric ? "internal forces of a ring sum to its "
                                  "hoop force" :
                                  "internal forces of a point sum to zero",
                   equilibrium < 1e-9 * force.l2_norm());

  // Central differences, column by column.
  const double       h     = 1e-6;
  double             error = 0.;
  const unsigned int n     = support.n_nodes * dim;
  for (unsigned int j = 0; j < n; ++j)
    {
      auto plus = du, minus = du;
      plus[j / dim][j % dim] += h;
      minus[j / dim][j % dim] -= h;
      Vector<double> f_plus, f_minus;
      evaluate(plus, f_plus, nullptr);
      evaluate(minus, f_minus, nullptr);
      for (unsigned int i = 0; i < n; ++i)
        error = std::max(error,
                         std::abs((f_plus(i) - f_minus(i)) / (2 * h) -
                                  tangent(i, j)));
    }
  mpm_tests::check("tangent = d(internal force)/d(displacement) to 1e-6 "
                   "relative (material + geometric)",
                   error < 1e-6 * tangent.frobenius_norm());
  FullMatrix<double> transposed;
  transposed.copy_transposed(tangent);
  transposed.add(-1., tangent);
  // Hyperelastic laws have a symmetric tangent; a tangent by central
  // differences (Hencky) is symmetric to the accuracy of the differences.
  const double symmetry_tolerance = model == "Hencky" ? 1e-8 : 1e-12;
  mpm_tests::check("tangent is symmetric to " +
                     std::string(model == "Hencky" ? "1e-8" : "1e-12"),
                   transposed.frobenius_norm() <
                     symmetry_tolerance * tangent.frobenius_norm());
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  for (const std::string model : {"neo-Hookean", "Hencky"})
    {
      test<2>(model);
      test<3>(model);
      test<2>(model, true);
    }
}
