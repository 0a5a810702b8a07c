// Contact between bodies (Bodies/<name>/Contact group, Contact/Pairs):
// each group moves in its own velocity field, and the fields meet through
// the Coulomb law at the nodes they share, checked against mechanics from
// outside the code.
// - prm/block_on_slope.prm: an elastic block on an elastic slab (the slope,
//   held by a fixed floor), gravity tilted by 30 degrees. A block that
//   slides with friction mu accelerates at a = g (sin 30 - mu cos 30); its
//   tracked centre's x(t) from t = 0.1 s (after the unstressed start has
//   settled) to 0.5 s, fitted by a parabola, gives a within 1 % for mu =
//   0 and 0.3 with linear shape functions, and for mu = 0.3 with uGIMP
//   and quadratic B-splines, whose wider supports share nodes a cell and
//   more inside the bodies. At every row the tangential sum is at most mu
//   times the normal sum, and at each node of the force files of the 11
//   output times |T| <= mu N; the normal force is the block's weight
//   across the slope, M g cos 30 = 679.7 N/m, within 2 % on average. With mu = 0.7 >
//   tan 30 (and a stiffer material, E = 1e8 Pa, so that the slab's shear
//   stays below a micrometre) the block sticks: it moves less than 1e-4 m.
// - prm/two_disks.prm with each disk in its own group, frictionless: the
//   disks close at 0.2 sqrt(2) m/s along the diagonal and their circles
//   would touch at t = 1.59 s; the boxes of their outermost points reach
//   0.025 sqrt(2) / 2 m beyond along the diagonal, so the points' surfaces
//   touch at 1.46 s. No contact force acts before that (one field couples
//   the disks from 1.18 s, as soon as they share nodes). The total
//   momentum stays zero (1e-12 of m v0): the law exchanges momentum
//   exactly. The disks separate: at 3.5 s no force acts, their centres are
//   more than 2 R apart, and the lower disk moves back.

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <utility>

#include "tests.h"

using namespace dealii;

namespace
{
  using Columns = mpm_tests::Columns;

  /** The scene's time series, run afresh into `directory`. */
  Columns
  run(const std::string &scene,
      const std::string &directory,
      const std::vector<std::string> &settings)
  {
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::filesystem::remove_all(directory);
    MPI_Barrier(MPI_COMM_WORLD);
    std::vector<std::string> all = {"Output/Write ParaView output=false"};
    all.insert(all.end(), settings.begin(), settings.end());
    return mpm_tests::run_scene(scene, directory, all);
  }

  /** a of x = c + b t + a t^2 / 2, least squares over t >= t0. */
  double
  fitted_acceleration(const std::vector<double> &t,
                      const std::vector<double> &x,
                      const double               t0)
  {
    // The normal equations of the basis 1, t, t^2.
    double A[3][4] = {};
    for (unsigned int n = 0; n < t.size(); ++n)
      if (t[n] >= t0)
        {
          const double phi[3] = {1., t[n], t[n] * t[n]};
          for (unsigned int i = 0; i < 3; ++i)
            {
              for (unsigned int j = 0; j < 3; ++j)
                A[i][j] += phi[i] * phi[j];
              A[i][3] += phi[i] * x[n];
            }
        }
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int k = i + 1; k < 3; ++k)
        {
          const double f = A[k][i] / A[i][i];
          for (unsigned int j = i; j < 4; ++j)
            A[k][j] -= f * A[i][j];
        }
    return 2. * A[2][3] / A[2][2];
  }

  void
  block_on_slope()
  {
    const double g = 9.81, theta = M_PI / 6., M = 1000. * 0.4 * 0.2;
    const std::vector<std::pair<std::string, std::string>> cases = {
      {"0", "linear"},
      {"0.3", "linear"},
      {"0.3", "uGIMP"},
      {"0.3", "quadratic B-spline"}};
    for (const auto &[friction, basis] : cases)
      {
        const double mu = std::stod(friction);
        deallog << "block on slope, mu = " << friction << ", " << basis
                << std::endl;
        auto csv = run("../prm/block_on_slope.prm",
                       "output-slope-mu" + friction + "-" +
                         basis.substr(0, basis.find(' ')),
                       {"Contact/Pairs=block-slope: " + friction,
                        "Grid/Shape functions=" + basis});
        const double exact = g * (std::sin(theta) - mu * std::cos(theta));
        const double a = fitted_acceleration(csv["time"], csv["point0_x"], 0.1);
        std::cout << "mu = " << mu << ", " << basis << ": a = " << a
                  << " (exact " << exact << ")" << std::endl;
        mpm_tests::check("a = g (sin 30 - mu cos 30) within 1 %",
                         std::abs(a - exact) < 0.01 * exact);
        bool   coulomb = true;
        double normal = 0.;
        unsigned int rows = 0;
        for (unsigned int n = 0; n < csv["time"].size(); ++n)
          {
            const double N = csv["slope_on_block_normal_force"][n];
            const double T = csv["slope_on_block_tangential_force"][n];
            coulomb = coulomb && N >= 0. && T <= mu * N * (1. + 1e-9) + 1e-9;
            if (csv["time"][n] >= 0.1)
              {
                normal += N;
                ++rows;
              }
          }
        mpm_tests::check("at every row, sum |T| <= mu sum N", coulomb);
        // The force files of the output times, node by node.
        unsigned int n_files = 0, n_nodes = 0;
        bool         node_coulomb = true;
        const std::string directory = "output-slope-mu" + friction + "-" +
                                      basis.substr(0, basis.find(' '));
        for (const auto &file : std::filesystem::directory_iterator(directory))
          if (file.path().filename().string().rfind("slope_on_block_forces_",
                                                    0) == 0)
            {
              ++n_files;
              // The file of the start lists no node: no solve came before.
              std::ifstream in(file.path());
              std::string   header, first;
              if (!std::getline(in, header) || !std::getline(in, first))
                continue;
              auto rows = mpm_tests::read_csv(file.path().string());
              for (unsigned int n = 0; n < rows["normal_force"].size(); ++n)
                {
                  const double N = rows["normal_force"][n];
                  const double T = rows["tangential_force"][n];
                  node_coulomb = node_coulomb && N >= 0. &&
                                 T <= (mu + 1e-9) * N;
                  ++n_nodes;
                }
            }
        mpm_tests::check("a force file at each of the 11 output times, "
                         "|T| <= mu N >= 0 at each of its nodes",
                         n_files == 11 && n_nodes > 50 && node_coulomb);
        mpm_tests::check("the mean normal force is M g cos 30 within 2 %",
                         std::abs(normal / rows - M * g * std::cos(theta)) <
                           0.02 * M * g * std::cos(theta));
      }

    deallog << "block on slope, mu = 0.7" << std::endl;
    auto csv = run("../prm/block_on_slope.prm",
                   "output-slope-stick",
                   {"Contact/Pairs=block-slope: 0.7",
                    "Materials/solid/Young's modulus=1e8"});
    const double moved = csv["point0_x"].back() - csv["point0_x"].front();
    mpm_tests::check("the block sticks (moves less than 1e-4 m)",
                     std::abs(moved) < 1e-4);
  }

  void
  two_disks()
  {
    deallog << "two disks, a group each" << std::endl;
    auto csv = run("../prm/two_disks.prm",
                   "output-disks-contact",
                   {"Bodies/lower disk/Contact group=lower",
                    "Bodies/upper disk/Contact group=upper"});
    const double v0 = 0.1, R = 0.2, h = 0.05;
    const double closing = 2. * std::sqrt(2.) * v0;
    const double gap     = 0.6 * std::sqrt(2.) - 2. * R;
    // Along the diagonal a point's box of side h / 2 reaches half its
    // diagonal, and both disks' boxes do.
    const double reach   = 2. * 0.5 * (h / 2.) * std::sqrt(2.);
    const double touch   = (gap - reach) / closing;
    const double m_v0    = 0.5 * csv["mass"][0] * v0 * std::sqrt(2.);
    double       first_force = -1., momentum = 0.;
    for (unsigned int n = 0; n < csv["time"].size(); ++n)
      {
        if (first_force < 0. && csv["lower_on_upper_normal_force"][n] != 0.)
          first_force = csv["time"][n];
        momentum = std::max(momentum,
                            std::hypot(csv["momentum_x"][n],
                                       csv["momentum_y"][n]));
      }
    std::cout << "first contact force at t = " << first_force
              << " s (points' surfaces touch at " << touch << " s)"
              << std::endl;
    mpm_tests::check("no contact before the points' surfaces touch",
                     first_force >= touch);
    mpm_tests::check("the disks meet", first_force > 0.);
    mpm_tests::check("the total momentum stays zero (1e-12 of m v0)",
                     momentum < 1e-12 * m_v0);
    const double distance =
      std::hypot(csv["point1_x"].back() - csv["point0_x"].back(),
                 csv["point1_y"].back() - csv["point0_y"].back());
    mpm_tests::check("they separate: no force at the end, centres more than "
                     "2 R apart, the lower disk moving back",
                     csv["lower_on_upper_normal_force"].back() == 0. &&
                       distance > 2. * R && csv["point0_vx"].back() < 0. &&
                       csv["point0_vy"].back() < 0.);
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  block_on_slope();
  two_disks();
}
