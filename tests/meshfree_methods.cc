// The Galerkin meshfree method (Method = GMM-MLS, GMM-LME) on the assembly
// that implicit MPM uses:
// - patch test, on a 16 x 16 cloud (interior nodes jittered by up to
//   0.2 h) with 2 x 2 Gauss points per cell: a
//   uniform stretch imposed on the nodes, u_I = (F - I) X_I, gives every
//   point dF = F to 1e-10 through PointAssembly::deformation_increment
//   (linear reproduction), with MLS and with LME (gamma 0.8, 1.8, 2.8).
//   The internal force of a uniform stress at nodes far from the boundary
//   is the point quadrature of sigma . int grad N_I, which vanishes exactly
//   only for a quadrature exact on grad N_I (MPM's Gauss points on Q1);
//   meshfree shape functions are not polynomials, and the size of that
//   quadrature error is printed, relative to |sigma| h, without a bound;
// - a block thrown with a uniform velocity under gravity
//   (tests/scenes/translating_block.prm, Newmark) moves as a rigid body
//   with each method: centre of mass at x0 + v t + g t^2 / 2 and momentum
//   m (v + g t) to 1e-10, strain energy below 1e-16 of the kinetic energy,
//   under gravity and with g = 0 (free flight, where Newton measures the
//   out-of-balance force against the momentum rate m v / dt).
//   This runs through the nodes' own velocity and acceleration history,
//   which GMM keeps from step to step;
// - the rolling disk of prm/rolling_disk.prm (Newmark, no-slip contact
//   plane) on h = 0.05 m to 0.1 s moves along the plane by 75 % to 105 %
//   of the exact rolling a t^2 / 2, a = 2/3 g sin 60 degrees
//   (benchmarks.md section 2; sliding gives 150 %, a stuck disk 0 %), and
//   its centre stays within 0.01 m of its height, as the MPM test in
//   implicit.cc asks;
// - the cantilever of prm/cantilever.prm at h = 0.5 m (quasi-static,
//   nonlinear, 5 load steps) converges with each method. Its tip
//   deflection, extrapolated from the four tracked points as
//   benchmarks/cantilever_self_weight does, is within 5 % of the reference
//   0.67433 m ([I] 5.1, benchmarks.md section 1) for both GMM bases; MPM on
//   the same grid is 10 % short (the benchmark's MPM table), so GMM lands
//   above MPM and below the reference.

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature_lib.h>

#include <mpm/assembly/point_assembly.h>
#include <mpm/basis/meshfree_basis.h>

#include <random>

#include "tests.h"

using namespace dealii;
using namespace mpm;
using mpm_tests::check;

/**
 * The patch test on a jittered cloud; returns the largest interior force
 * of a uniform stress relative to |sigma| h.
 */
double
patch_test(const MeshfreeBasis<2>::Kind kind, const double gamma)
{
  const std::string name =
    kind == MeshfreeBasis<2>::Kind::mls ?
      std::string("MLS") :
      "LME gamma " + std::to_string(gamma).substr(0, 3);
  const double       h = 0.25;
  const unsigned int n = 16;
  // Interior nodes jittered by up to 0.2 h: on a square cloud the
  // shape functions are symmetric and the quadrature error cancels.
  std::mt19937                           random(7);
  std::uniform_real_distribution<double> jitter(-0.2 * h, 0.2 * h);
  std::vector<Point<2>>                  nodes;
  for (unsigned int j = 0; j <= n; ++j)
    for (unsigned int i = 0; i <= n; ++i)
      {
        const bool inside = i > 0 && i < n && j > 0 && j < n;
        nodes.emplace_back(i * h + (inside ? jitter(random) : 0.),
                           j * h + (inside ? jitter(random) : 0.));
      }
  MeshfreeBasis<2>::Settings settings;
  settings.kind      = kind;
  settings.spacing   = h;
  settings.lme_gamma = gamma;
  MeshfreeBasis<2> basis(settings);
  basis.reinit(nodes);

  Tensor<2, 2> F;
  F[0][0] = 1.2;
  F[0][1] = 0.1;
  F[1][0] = 0.05;
  F[1][1] = 0.9;
  SymmetricTensor<2, 3> sigma;
  sigma[0][0] = 3.;
  sigma[1][1] = -1.;
  sigma[0][1] = 0.5;
  sigma[2][2] = 1.;

  const QGauss<2>             gauss(2);
  Support<2>                  support;
  std::vector<Tensor<1, 2>>   u;
  std::vector<Tensor<1, 2>>   force_at_node(nodes.size());
  PointAssembly<2>::Scratch   scratch;
  double                      dF_error = 0.;
  for (unsigned int j = 0; j < n; ++j)
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int q = 0; q < gauss.size(); ++q)
        {
          const Point<2> x(h * (i + gauss.point(q)[0]),
                           h * (j + gauss.point(q)[1]));
          basis.evaluate(x, support);
          u.resize(support.n_nodes);
          for (unsigned int k = 0; k < support.n_nodes; ++k)
            u[k] = (F - unit_symmetric_tensor<2>()) * nodes[support.nodes[k]];
          const Tensor<2, 2> dF =
            PointAssembly<2>::deformation_increment(support, u);
          dF_error = std::max(dF_error, (dF - F).norm());

          PointAssembly<2>::internal_force(support,
                                           nullptr,
                                           h * h * gauss.weight(q),
                                           sigma,
                                           nullptr,
                                           nullptr,
                                           scratch);
          for (unsigned int k = 0; k < support.n_nodes; ++k)
            for (unsigned int a = 0; a < 2; ++a)
              force_at_node[support.nodes[k]][a] += scratch.force[k * 2 + a];
        }
  check(name + ": a uniform stretch on the nodes gives dF = F at every "
               "point to 1e-10",
        dF_error < 1e-10);

  // Nodes whose whole support lies inside the block.
  const double reach = basis.search_radius() + h;
  double       interior = 0.;
  for (unsigned int k = 0; k < nodes.size(); ++k)
    {
      const Point<2> &x = nodes[k];
      if (x[0] > reach && x[0] < n * h - reach && x[1] > reach &&
          x[1] < n * h - reach)
        interior = std::max(interior, force_at_node[k].norm());
    }
  deallog << name << ": interior internal force of a uniform stress, "
          << "relative to |sigma| h: " << std::setprecision(2)
          << interior / (sigma.norm() * h) << std::setprecision(6)
          << std::endl;
  // The quadrature of rational (MLS) and exponential (LME) shape functions
  // is inexact, so the interior force is not zero (0.5-13 % measured); a
  // wrong gradient or weight would give a force of the order of |sigma| h.
  check(name + ": interior force of a uniform stress below 0.2 |sigma| h",
        interior < 0.2 * sigma.norm() * h);
  // Exact, whatever the quadrature: the gradients of a partition of unity
  // sum to zero at every point, so the forces on all nodes balance.
  Tensor<1, 2> total;
  for (const Tensor<1, 2> &f : force_at_node)
    total += f;
  check(name + ": the forces on all nodes sum to zero to 1e-12 |sigma| area",
        total.norm() < 1e-12 * sigma.norm() * (n * h) * (n * h));
  return interior / (sigma.norm() * h);
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  patch_test(MeshfreeBasis<2>::Kind::mls, 0.);
  std::vector<double> lme_error;
  for (const double gamma : {0.8, 1.8, 2.8})
    lme_error.push_back(patch_test(MeshfreeBasis<2>::Kind::lme, gamma));
  // Smaller gamma, smoother shape functions, a better quadrature.
  check("LME: the interior force grows with gamma (0.8, 1.8, 2.8)",
        lme_error[0] < lme_error[1] && lme_error[1] < lme_error[2]);

  // Under gravity, and in free flight: without any force the Newton scale
  // is the momentum rate m v / dt, not round-off against round-off.
  for (const std::string method : {"MPM", "GMM-MLS", "GMM-LME"})
    for (const double g : {9.81, 0.})
      {
        const std::string flight = g > 0. ? "under gravity" : "in free flight";
        auto csv = mpm_tests::run_scene(
          "scenes/translating_block.prm",
          "output-translating-" + method + (g > 0. ? "" : "-free"),
          {"Method=" + method, "Gravity=0, " + std::to_string(-g)});
        const unsigned int last = csv["time"].size() - 1;
        const double       t    = csv["time"][last];
        const double       mass = csv["mass"][0];
        const bool         moved =
          std::abs(csv["centre_of_mass_x"][last] -
                   (csv["centre_of_mass_x"][0] + 2. * t)) < 1e-10 &&
          std::abs(csv["centre_of_mass_y"][last] -
                   (csv["centre_of_mass_y"][0] + t - g * t * t / 2.)) <
            1e-10 &&
          std::abs(csv["momentum_x"][last] - 2. * mass) < 1e-10 * mass &&
          std::abs(csv["momentum_y"][last] - (1. - g * t) * mass) <
            1e-10 * mass;
        check(method + ": a block in uniform motion " + flight +
                " translates rigidly over " + std::to_string(last) + " steps",
              moved && t > 0.19);
        check(method + ": and stays unstrained",
              csv["strain_energy"][last] < 1e-16 * csv["kinetic_energy"][last]);
      }

  // The rolling disk (prm/rolling_disk.prm, Newmark, a no-slip contact
  // plane) on h = 0.05 m to 0.1 s: the cloud's nodes are held where the
  // material reaches the plane and let go where the plane would pull.
  for (const std::string method : {"GMM-MLS", "GMM-LME"})
    {
      auto csv = mpm_tests::run_scene("../prm/rolling_disk.prm",
                                      "output-rolling-" + method,
                                      {"Method=" + method,
                                       "Time stepping/End time=0.1"});
      const double t = csv["time"].back();
      const auto [ratio, drift] = mpm_tests::rolling_disk_ratio_and_drift(csv);
      check(method + ": the disk rolls (75 % to 105 % of a t^2 / 2 at 0.1 s; "
                     "sliding gives 150 %)",
            t > 0.1 - 1e-9 && ratio > 0.75 && ratio < 1.05);
      check(method + ": the disk stays on the plane: centre height within "
                     "0.01 m",
            drift < 0.01);
    }

  for (const std::string method : {"GMM-MLS", "GMM-LME"})
    mpm_tests::check_plastic_tangent(method);

  const double reference = 0.67433;
  std::map<std::string, double> tip;
  for (const std::string method : {"MPM", "GMM-MLS", "GMM-LME"})
    {
      auto csv = mpm_tests::run_scene("../prm/cantilever.prm",
                                      "output-cantilever-" + method,
                                      {"Method=" + method});
      // Bilinear extrapolation to (8, 0.5) of the four tracked points.
      double v[4];
      for (unsigned int k = 0; k < 4; ++k)
        {
          const auto &y = csv["point" + std::to_string(k) + "_y"];
          v[k]          = y.back() - y.front();
        }
      const auto & x0 = csv["point0_x"], x1 = csv["point1_x"];
      const auto & y0 = csv["point0_y"], y2 = csv["point2_y"];
      const double s  = (8. - x0[0]) / (x1[0] - x0[0]);
      const double r  = (0.5 - y0[0]) / (y2[0] - y0[0]);
      tip[method] = -((1 - s) * (1 - r) * v[0] + s * (1 - r) * v[1] +
                      (1 - s) * r * v[2] + s * r * v[3]);
      deallog << method << ": tip deflection " << std::setprecision(3)
              << tip[method] << " m" << std::setprecision(6) << std::endl;
      check(method + ": the cantilever reaches full load",
            std::abs(csv["time"].back() - 1.) < 1e-12);
    }
  for (const std::string method : {"GMM-MLS", "GMM-LME"})
    check(method + ": tip within 5 % of 0.67433 m and beyond MPM's",
          std::abs(tip[method] - reference) < 0.05 * reference &&
            tip[method] > tip["MPM"]);
}
