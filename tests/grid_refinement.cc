// The grid changes in the middle of a run: explicit MPM (MUSL) of a block
// in free fall, the grid refined once globally after 10 steps, then 10
// steps more, in 2D and 3D, on one or two ranks. Grid::refine_globally
// announces the change and everything keyed by cells or nodes rebuilds on
// it: the points are carried into the refined cells (deal.II's particle
// transfer), the nodal storage and the boundary conditions number the new
// nodes, and the step's one-cell check takes the new cell size.
// - no point is lost, and the grid has 2^dim times the cells;
// - free fall stays exact: every point has v = -g t_n, and the centre of
//   mass follows MUSL's discrete y_n = y_0 - g t_n (t_n + dt) / 2, both to
//   round-off, across the refinement;
// - one projection to the refined grid conserves mass and momentum to
//   round-off.

#include <deal.II/base/mpi.h>

#include <mpm/assembly/grid_transfer.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>
#include <mpm/time/explicit_integrator.h>

#include <cmath>

#include "small_scene.h"
#include "tests.h"

using namespace dealii;
using namespace mpm;

template <int dim>
void
test()
{
  deallog << "dim = " << dim << std::endl;
  const double   g = 9.81;

  ParameterHandler prm;
  mpm_tests::parse_small_scene<dim>(prm,
                                    mpm_tests::block_in_unit_box<dim>());
  Tensor<1, dim> gravity;
  gravity[dim - 1] = -g;
  mpm_tests::SmallExplicitRun<dim> run(prm, gravity);
  auto &[grid, dirichlet, nodes, basis, materials, points, transfer, timer,
         integrator] = run;

  const types::particle_index n_points = points.n_global_points();
  const unsigned int          n_cells =
    grid.get_triangulation().n_global_active_cells();
  const auto [velocity_error, height_error] =
    mpm_tests::free_fall_errors(run, g, [&](const unsigned int n) {
      if (n == 11)
        grid.refine_globally(1);
    });

  mpm_tests::check("no point lost across the refinement",
                   points.n_global_points() == n_points);
  mpm_tests::check("the grid has 2^dim times the cells",
                   grid.get_triangulation().n_global_active_cells() ==
                     (1u << dim) * n_cells);
  mpm_tests::check("free fall across the refinement: v = -g t_n to 1e-12",
                   velocity_error < 1e-12);
  mpm_tests::check("and y_n = y_0 - g t_n (t_n + dt) / 2 to 1e-12",
                   height_error < 1e-12);
  mpm_tests::check_projection_conserves(run, "projection to the refined grid");
  deallog << "points: " << points.n_global_points() << ", cells "
          << n_cells << " -> "
          << grid.get_triangulation().n_global_active_cells() << std::endl;
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  test<2>();
  test<3>();
}
