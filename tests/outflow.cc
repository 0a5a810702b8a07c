// A wall that ends and an outflow boundary (scenes/opening_floor.prm): an
// elastic block rests on a fixed floor 'until 0.1', which is also an
// outflow boundary, and then falls out of the grid. Checked against
// mechanics:
// - while the floor holds, the block rests: its centre of mass moves by
//   less than 1 mm (free fall would take it 49 mm in 0.1 s; it settles by
//   rho g H^2 / (2 E) = 0.2 mm);
// - once the floor is gone and before the first point leaves, nothing but
//   gravity acts on the block, so its momentum falls by M g per second to
//   round-off (internal forces sum to zero);
// - mass is conserved with the outflow counted: mass + removed_mass = M at
//   every row, to round-off; at the end every point is removed, the
//   removed mass is M and the run ends with exit code 0;
// - without the outflow boundary the block leaves the grid and the run
//   stops with exit code 3 (a run that cannot go on).

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>

#include "tests.h"

using namespace dealii;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  const double g = 9.81;

  auto csv = mpm_tests::run_scene("scenes/opening_floor.prm", "output-open");
  const double M  = csv["mass"][0];
  const double N0 = csv["points"][0];
  double       settle = 0., mass_gap = 0., fall_gap = 0.;
  int          first_free = -1;
  unsigned int free_rows  = 0;
  for (unsigned int n = 0; n < csv["time"].size(); ++n)
    {
      const double t = csv["time"][n];
      mass_gap =
        std::max(mass_gap, std::abs(csv["mass"][n] + csv["removed_mass"][n] - M));
      if (t <= 0.1)
        settle = std::max(settle,
                          std::abs(csv["centre_of_mass_y"][n] -
                                   csv["centre_of_mass_y"][0]));
      // Rows of steps that start at 0.1 or later, before any removal.
      else if (csv["time"][n] - csv["dt"][n] >= 0.1 - 1e-12 &&
               csv["removed_points"][n] == 0.)
        {
          if (first_free < 0)
            first_free = n - 1;
          const double t0 = csv["time"][first_free];
          fall_gap        = std::max(
            fall_gap,
            std::abs(csv["momentum_y"][n] - csv["momentum_y"][first_free] +
                     M * g * (t - t0)) /
              (M * g * (t - t0)));
          ++free_rows;
        }
    }
  deallog << "settled by " << settle << " m; " << free_rows
          << " steps of free fall; removed " << csv["removed_points"].back()
          << " of " << N0 << " points" << std::endl;
  mpm_tests::check("the floor holds the block until 0.1 s (less than 1 mm)",
                   settle < 1e-3);
  mpm_tests::check("then free fall: momentum falls by M g t to 1e-9",
                   free_rows > 10 && fall_gap < 1e-9);
  mpm_tests::check("mass + removed mass = M at every row, to 1e-12 M",
                   mass_gap < 1e-12 * M);
  mpm_tests::check("every point is removed, with the block's mass, to "
                   "1e-12",
                   csv["points"].back() == 0. &&
                     csv["removed_points"].back() == N0 &&
                     std::abs(csv["removed_mass"].back() - M) < 1e-12 * M);

  int code = 0;
  mpm_tests::run_scene("scenes/opening_floor.prm",
                       "output-no-outflow",
                       {"Boundary conditions/Outflow boundaries="},
                       nullptr,
                       &code);
  mpm_tests::check("without the outflow boundary the run stops (exit 3)",
                   code == 3);
  return 0;
}
