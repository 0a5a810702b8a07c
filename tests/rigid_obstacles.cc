// A rigid obstacle that moves (Obstacles, explicit MUSL): a box ram at a
// constant 1 m/s pushes a soft von Mises block along a frictionless floor
// (scenes/pushed_block.prm), checked against mechanics from outside the
// code:
// - Newton's third law: the block's momentum is the impulse of the force
//   the ram feels, -sum dt F_x, to round-off (the ram's force is the only
//   one on the block);
// - the ram is impenetrable: the block's rearmost point stays ahead of
//   the ram's face, x_face = 0.5 + t, less one cell (the grid sees the
//   ram at its nodes);
// - the block is pushed: it ends moving along x at no less than the ram's
//   speed and no more than twice it (what an elastic body takes from a
//   rigid wall that moves, the bound for any material);
// - Coulomb at the ram's nodes: at every step the sums over its nodes
//   meet sum |T| <= mu sum N, and at each output time every node of the
//   force file has |T| <= mu N, N >= 0.
// All of it with the lumped and with the blended mass (whose change at the
// ram's nodes passes through the ram's law again). The same scene with the
// ram standing still, away from the block, leaves the block at rest.

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "tests.h"

using namespace dealii;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  const double V = 1., h = 0.05, mu = 0.3;

  // The pushed block with the given mass matrix; returns M.
  const auto pushed_block = [&](const std::string &mass_matrix) {
    const std::string directory = "output-pushed-" + mass_matrix;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::filesystem::remove_all(directory);
    MPI_Barrier(MPI_COMM_WORLD);
    deallog << "Time stepping/Mass matrix = " << mass_matrix << std::endl;
    auto csv = mpm_tests::run_scene("scenes/pushed_block.prm",
                                    directory,
                                    {"Time stepping/Mass matrix=" +
                                     mass_matrix});
    const double M       = csv["mass"][0];
    double       impulse = 0., balance = 0.;
    double       penetration = -std::numeric_limits<double>::max();
    double       bound       = -std::numeric_limits<double>::max();
    double       pushing = 0.;
    for (unsigned int n = 1; n < csv["time"].size(); ++n)
      {
        impulse -= csv["dt"][n] * csv["ram_force_x"][n];
        balance = std::max(balance, std::abs(csv["momentum_x"][n] - impulse));
        penetration =
          std::max(penetration, 0.5 + V * csv["time"][n] - csv["min_x"][n]);
        pushing = std::max(pushing, -csv["ram_force_x"][n]);
        // Sums over the ram's nodes of |T| and N: each node meets Coulomb.
        bound = std::max(bound,
                         csv["ram_tangential_force"][n] -
                           mu * csv["ram_normal_force"][n]);
      }
    const double v_end = csv["momentum_x"].back() / M;
    deallog << "largest push " << pushing << " N/m; end velocity " << v_end
            << " m/s; largest x_face - x_rearmost " << penetration << " m"
            << std::endl;
    mpm_tests::check("the block's momentum is the ram's impulse to 1e-9 M V",
                     pushing > 0. && balance < 1e-9 * M * V);
    mpm_tests::check("at every step the ram's nodes meet Coulomb: sum |T| <= "
                     "mu sum N, to 1e-9 of the largest push",
                     bound < 1e-9 * pushing);
    mpm_tests::check("the block stays ahead of the ram's face, less a cell",
                     penetration < h);
    mpm_tests::check("the block ends between the ram's speed and twice it",
                     v_end > 0.99 * V && v_end < 2.01 * V);

    unsigned int files = 0, nodes = 0;
    bool         coulomb = true;
    for (const auto &entry : std::filesystem::directory_iterator(directory))
      if (entry.path().filename().string().rfind("ram_forces_", 0) == 0)
        {
          ++files;
          std::ifstream in(entry.path());
          std::string   line;
          std::getline(in, line);
          while (std::getline(in, line))
            {
              double x, y, normal, tangential;
              char   comma;
              std::istringstream row(line);
              row >> x >> comma >> y >> comma >> normal >> comma >> tangential;
              ++nodes;
              coulomb &=
                normal >= 0. && tangential <= mu * normal * (1. + 1e-11);
            }
        }
    deallog << files << " force files, " << nodes << " node rows" << std::endl;
    mpm_tests::check("at the ram's nodes N >= 0 and |T| <= mu N",
                     files > 0 && nodes > 0 && coulomb);
    return M;
  };
  // The blended mass applies the ram's law again to its change at the
  // ram's nodes, so the reported force stays the one that moves the block.
  const double M = pushed_block("lumped");
  pushed_block("blended");

  auto alone = mpm_tests::run_scene("scenes/pushed_block.prm",
                                    "output-alone",
                                    {"Obstacles/ram/Displacement=0; 0"});
  mpm_tests::check("a standing ram away from the block leaves it at rest",
                   std::abs(alone["momentum_x"].back()) < 1e-12 * M * V);
  return 0;
}
