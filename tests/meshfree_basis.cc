// Meshfree shape functions (MeshfreeBasis), MLS and LME with gamma = 0.8,
// 1.8 and 2.8, in 2D and 3D, on clouds of nodes jittered by up to 0.3 h
// from a square grid, at random points that are at least one spacing
// inside the cloud:
// - partition of unity and linear reproduction, the two properties the
//   assembly relies on (a uniform stretch is then exact): sum N = 1,
//   sum N x_I = x, sum grad N = 0 and sum grad N (x) x_I = I, to 1e-10
//   (lengths in units of h);
// - the gradients against central differences of N (step 1e-5 h), to
//   1e-6 of the largest gradient; points whose support changes within
//   the step (an LME node crossing the 1e-6 cut-off) are skipped and
//   counted;
// - the R-tree finds exactly the nodes a brute-force search finds;
// - LME on a square grid, 1e-6 h inside a face of the cloud: the nodes off
//   the face carry together less than 2e-6 (weak Kronecker-delta property),
//   and 1e-6 h inside a corner the corner node carries more than 1 - 1e-5
//   (MLS, whose values can be negative, has no such property);
// - a point in a gap of the cloud gets nodes by growing the radius; a
//   point outside the cloud stops with a message that names its position.

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <mpm/basis/meshfree_basis.h>
#include <mpm/base/input_error.h>

#include <random>

#include "tests.h"

using namespace dealii;
using namespace mpm;
using mpm_tests::check;

template <int dim>
std::vector<Point<dim>>
grid_cloud(const unsigned int n, const double h, const double jitter,
           std::mt19937 &random)
{
  std::uniform_real_distribution<double> offset(-jitter * h, jitter * h);
  std::vector<Point<dim>>                cloud;
  const unsigned int n_total = dim == 2 ? n * n : n * n * n;
  for (unsigned int i = 0; i < n_total; ++i)
    {
      Point<dim>   x;
      unsigned int rest = i;
      for (unsigned int d = 0; d < dim; ++d, rest /= n)
        x[d] = (rest % n) * h + (jitter > 0. ? offset(random) : 0.);
      cloud.push_back(x);
    }
  return cloud;
}

template <int dim>
typename MeshfreeBasis<dim>::Settings
settings_of(const bool lme, const double gamma, const double h)
{
  typename MeshfreeBasis<dim>::Settings s;
  s.kind      = lme ? MeshfreeBasis<dim>::Kind::lme :
                      MeshfreeBasis<dim>::Kind::mls;
  s.lme_gamma = gamma;
  s.spacing   = h;
  return s;
}

template <int dim>
void
check_reproduction(const bool lme, const double gamma)
{
  const std::string name = std::string(lme ? "LME gamma " : "MLS") +
                           (lme ? std::to_string(gamma).substr(0, 3) : "") +
                           " " + std::to_string(dim) + "D";
  const double       h = 0.1;
  const unsigned int n = dim == 2 ? 14 : 8;
  std::mt19937       random(17 + dim);
  MeshfreeBasis<dim> basis(settings_of<dim>(lme, gamma, h));
  basis.reinit(grid_cloud<dim>(n, h, 0.3, random));
  const auto &nodes = basis.node_positions();

  std::uniform_real_distribution<double> inside(1.5 * h, (n - 2.5) * h);
  double       unity = 0., linear = 0., grad_sum = 0., grad_linear = 0.,
         fd_error = 0., largest_gradient = 0.;
  unsigned int skipped = 0, tree_mismatches = 0, max_nodes = 0;
  const unsigned int n_points = dim == 2 ? 200 : 60;
  Support<dim>       support, plus, minus;
  for (unsigned int q = 0; q < n_points; ++q)
    {
      Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = inside(random);
      basis.evaluate(x, support);
      max_nodes = std::max(max_nodes, support.n_nodes);

      double         sum_N = 0.;
      Tensor<1, dim> sum_Nx, sum_grad;
      Tensor<2, dim> sum_grad_x;
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          const Point<dim> &xi = nodes[support.nodes[i]];
          sum_N += support.N[i];
          sum_Nx += support.N[i] * xi;
          sum_grad += support.grad_N[i];
          sum_grad_x += outer_product(xi, support.grad_N[i]);
          largest_gradient =
            std::max(largest_gradient, support.grad_N[i].norm() * h);
        }
      unity       = std::max(unity, std::abs(sum_N - 1.));
      linear      = std::max(linear, (sum_Nx - x).norm() / h);
      grad_sum    = std::max(grad_sum, sum_grad.norm() * h);
      grad_linear = std::max(
        grad_linear, (sum_grad_x - unit_symmetric_tensor<dim>()).norm());

      // The support is every node within the first radius (none of these
      // points needs a larger one).
      unsigned int within = 0;
      for (const auto &node : nodes)
        within += (node - x).norm() < basis.search_radius();
      tree_mismatches += within != support.n_nodes;

      // Central differences, node by node.
      const double delta = 1e-5 * h;
      for (unsigned int k = 0; k < dim; ++k)
        {
          Point<dim> xp = x, xm = x;
          xp[k] += delta;
          xm[k] -= delta;
          basis.evaluate(xp, plus);
          basis.evaluate(xm, minus);
          if (plus.n_nodes != support.n_nodes ||
              minus.n_nodes != support.n_nodes ||
              !std::equal(plus.nodes.begin(),
                          plus.nodes.begin() + plus.n_nodes,
                          support.nodes.begin()) ||
              !std::equal(minus.nodes.begin(),
                          minus.nodes.begin() + minus.n_nodes,
                          support.nodes.begin()))
            {
              ++skipped;
              continue;
            }
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            fd_error = std::max(fd_error,
                                std::abs((plus.N[i] - minus.N[i]) /
                                           (2. * delta) -
                                         support.grad_N[i][k]) *
                                  h);
        }
    }
  deallog << name << ": up to " << max_nodes << " nodes per point"
          << std::endl;
  check(name + ": sum N = 1 to 1e-10", unity < 1e-10);
  check(name + ": sum N x_I = x to 1e-10 h", linear < 1e-10);
  check(name + ": sum grad N = 0 to 1e-10 / h", grad_sum < 1e-10);
  check(name + ": sum grad N (x) x_I = I to 1e-10", grad_linear < 1e-10);
  check(name + ": gradients match central differences to 1e-6 of the "
               "largest",
        fd_error < 1e-6 * largest_gradient);
  check(name + ": fewer than 5 % of difference pairs skipped",
        skipped < 0.05 * dim * n_points);
  check(name + ": the R-tree finds the brute-force neighbours",
        tree_mismatches == 0);
}

template <int dim>
void
check_kronecker_delta()
{
  const double       h = 0.5, epsilon = 1e-6 * h;
  const unsigned int n = 6;
  std::mt19937       random(3);
  MeshfreeBasis<dim> basis(settings_of<dim>(true, 1.8, h));
  basis.reinit(grid_cloud<dim>(n, h, 0., random));
  const auto &nodes = basis.node_positions();
  const std::string name = "LME " + std::to_string(dim) + "D";

  std::uniform_real_distribution<double> along(h, (n - 2) * h);
  Support<dim>                           support;
  double                                 off_face = 0.;
  for (unsigned int q = 0; q < 20; ++q)
    {
      Point<dim> x;
      x[0] = epsilon;
      for (unsigned int d = 1; d < dim; ++d)
        x[d] = along(random);
      basis.evaluate(x, support);
      double weight = 0.;
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        if (nodes[support.nodes[i]][0] > 0.5 * h)
          weight += std::abs(support.N[i]);
      off_face = std::max(off_face, weight);
    }
  check(name + ": nodes off a face carry less than 2e-6 at 1e-6 h from it",
        off_face < 2e-6);

  Point<dim> corner;
  for (unsigned int d = 0; d < dim; ++d)
    corner[d] = epsilon;
  basis.evaluate(corner, support);
  double corner_value = 0.;
  for (unsigned int i = 0; i < support.n_nodes; ++i)
    if (nodes[support.nodes[i]].norm() < 1e-12)
      corner_value = support.N[i];
  check(name + ": the corner node carries more than 1 - 1e-5 at 1e-6 h "
               "from it",
        corner_value > 1. - 1e-5);
}

template <int dim>
void
check_growth_and_failure()
{
  const double h = 1.;
  std::mt19937 random(5);
  for (const bool lme : {false, true})
    {
      const std::string name = std::string(lme ? "LME" : "MLS") + " " +
                               std::to_string(dim) + "D";
      // A square cloud with its middle nodes taken out.
      std::vector<Point<dim>> cloud;
      for (const auto &x : grid_cloud<dim>(9, h, 0., random))
        {
          bool in_gap = true;
          for (unsigned int d = 0; d < dim; ++d)
            in_gap = in_gap && std::abs(x[d] - 4. * h) < 2.5 * h;
          if (!in_gap)
            cloud.push_back(x);
        }
      MeshfreeBasis<dim> basis(settings_of<dim>(lme, 2.8, h));
      basis.reinit(cloud);
      Support<dim> support;
      Point<dim>   middle;
      for (unsigned int d = 0; d < dim; ++d)
        middle[d] = 4. * h;
      basis.evaluate(middle, support);
      double sum_N = 0.;
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        sum_N += support.N[i];
      check(name + ": a point in a gap grows its radius and keeps sum N = 1",
            basis.statistics().radius_growths == 1 &&
              std::abs(sum_N - 1.) < 1e-10);

      // LME needs the point inside the hull of its nodes; MLS extrapolates
      // and fails only where it finds too few nodes.
      Point<dim> outside = middle;
      outside[0]         = (lme ? -3. : -8.) * h;
      try
        {
          basis.evaluate(outside, support);
          check(name + ": a point outside the cloud stops the run", false);
        }
      catch (const RunError &e)
        {
          deallog << e.what() << std::endl;
          check(name + ": a point outside the cloud stops the run", true);
        }
    }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  try
  {
  for (const bool lme : {false, true})
    for (const double gamma : lme ? std::vector<double>{0.8, 1.8, 2.8} :
                                    std::vector<double>{0.})
      {
        check_reproduction<2>(lme, gamma);
        check_reproduction<3>(lme, gamma);
      }
  check_kronecker_delta<2>();
  check_kronecker_delta<3>();
  check_growth_and_failure<2>();
  check_growth_and_failure<3>();
  }
  catch (const std::exception &e)
  {
    deallog << "FAIL: " << e.what() << std::endl;
    return 1;
  }
}
