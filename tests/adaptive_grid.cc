// A grid that is refined in part: the hanging vertices on the faces
// between coarse and fine cells pass their shape functions to the nodes of
// the coarse face, in 2D and 3D, on one or two ranks.
// - the shape functions at points in every cell (fine, coarse, and fine
//   cells with hanging vertices) are a partition of unity that reproduces
//   linear fields (values and gradients), reach no hanging node, and are
//   continuous across a coarse-fine face;
// - a block in free fall across refinement and coarsening mid-run (with
//   hanging nodes around it) falls exactly: v = -g t_n at every point and
//   MUSL's y_n = y_0 - g t_n (t_n + dt) / 2 for the centre of mass; a
//   projection to the refined grid conserves mass and momentum;
// - a uniform stress in a box filled with material (slip walls) whose
//   grid is refined in one half stays uniform, at rest: the internal
//   forces at the nodes of the coarse-fine interface cancel;
// - a granular column collapse (prm/granular_collapse.prm, 0.06 s) on a
//   grid that follows the material gives the time series of the uniform
//   grid of its finest cells to round-off (the Margin keeps every cell
//   with material and its neighbours at the finest level, so the same
//   nodes carry the same sums), with fewer cells; and a run continued
//   from a checkpoint written after the grid adapted repeats the run made
//   in one go to the last digit;
// - Finer levels on the same collapse: a Finer region over the whole box
//   gives the time series of the grid refined once more everywhere (and
//   so of the uniform grid); one over the column's toe (x > 0.15 m), and
//   finer levels where the material flows, end
//   with more cells than the grid refined once and fewer than the one
//   refined twice, and a run continued from a checkpoint repeats the run
//   made in one go to the last digit;
// - the cohesive column collapse with Newmark (prm/column_collapse.prm,
//   0.6 s) on the adaptive grid gives the uniform grid's time series to
//   round-off with Margin = 2, and with Margin = 0 (the material's cells
//   have hanging vertices, condensed in the implicit system too) Newton
//   converges and the centre of mass stays within 1 % of the uniform
//   grid's;
// - a block falling away from a rigid obstacle smaller than the finest
//   cell (scenes/obstacle_left_behind.prm): the cells around the obstacle
//   coarsen once the block has left, until no node lies within the finest
//   cell of it; the run goes on to its end (the obstacle's reach is
//   checked on the first grid only; checked at every grid change, the run
//   stopped at t = 0.24 s with an input error).

#include <deal.II/base/mpi.h>

#include <mpm/assembly/grid_transfer.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>
#include <mpm/time/explicit_integrator.h>

#include <cmath>
#include <map>
#include <sstream>

#include "small_scene.h"
#include "tests.h"

using namespace dealii;
using namespace mpm;

namespace
{
  /** Refine the owned cells whose centre lies below x = `x` once. */
  template <int dim>
  void
  refine_left_of(Grid<dim> &grid, const double x)
  {
    grid.adapt([x](const auto &cell) { return cell->center()[0] < x ? 1 : 0; });
  }



  /** A point of the reference cell, from a seed, away from its faces. */
  template <int dim>
  Point<dim>
  sample_point(const unsigned int k)
  {
    Point<dim> xi;
    for (unsigned int d = 0; d < dim; ++d)
      xi[d] = 0.05 + 0.9 * std::fmod(0.6180339887 * (k + 1) * (d + 2), 1.);
    return xi;
  }
} // namespace



template <int dim>
void
check_shape_functions()
{
  const MPI_Comm   comm = MPI_COMM_WORLD;
  ParameterHandler prm;
  mpm_tests::parse_small_scene<dim>(
    prm,
    "subsection Grid\n set Generator = subdivided_hyper_cube\n"
    " set Arguments = 4 : 0 : 1 : true\nend\n");
  Grid<dim> grid(prm, comm);
  grid.create();
  refine_left_of(grid, 0.5);
  refine_left_of(grid, 0.25);
  const GridBasis<dim> basis(grid);
  const auto &         hanging = grid.hanging_node_constraints();
  const auto &         partitioner = *grid.node_partitioner();

  double       unity = 0., reproduction = 0., gradient = 0., continuity = 0.;
  bool         reaches_hanging = false;
  unsigned int n_hanging_cells = 0, n_faces = 0;
  Support<dim> support, other;
  for (const auto &cell : grid.get_triangulation().active_cell_iterators())
    {
      if (!cell->is_locally_owned())
        continue;
      const unsigned int index = cell->active_cell_index();
      n_hanging_cells += grid.cell_geometry(index).n_hanging > 0;
      for (unsigned int k = 0; k < 5; ++k)
        {
          const Point<dim> xi = sample_point<dim>(k + index);
          const Point<dim> x =
            grid.get_mapping().transform_unit_to_real_cell(cell, xi);
          basis.evaluate(index, xi, {}, support);
          double         sum = 0.;
          Tensor<1, dim> sum_gradient, position;
          Tensor<2, dim> position_gradient;
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            {
              const Point<dim> &node = grid.node_position(support.nodes[i]);
              sum += support.N[i];
              sum_gradient += support.grad_N[i];
              position += support.N[i] * node;
              position_gradient += outer_product(node, support.grad_N[i]);
              reaches_hanging =
                reaches_hanging ||
                hanging.is_constrained(
                  partitioner.local_to_global(support.nodes[i]));
            }
          unity        = std::max(unity, std::abs(sum - 1.));
          reproduction = std::max(reproduction, (position - x).norm());
          gradient     = std::max(gradient,
                              (sum_gradient.norm() +
                               (position_gradient -
                                unit_symmetric_tensor<dim>())
                                 .norm()));
        }

      // On each face towards a coarser owned neighbour, the functions seen
      // from both sides agree.
      for (const unsigned int f : cell->face_indices())
        {
          if (cell->at_boundary(f) || !cell->neighbor_is_coarser(f) ||
              !cell->neighbor(f)->is_locally_owned())
            continue;
          ++n_faces;
          const auto coarse = cell->neighbor(f);
          for (unsigned int k = 0; k < 3; ++k)
            {
              Point<dim> xi = sample_point<dim>(k);
              xi[f / 2]     = f % 2;
              const Point<dim> x =
                grid.get_mapping().transform_unit_to_real_cell(cell, xi);
              basis.evaluate(index, xi, {}, support);
              basis.evaluate(
                coarse->active_cell_index(),
                grid.get_mapping().transform_real_to_unit_cell(coarse, x),
                {},
                other);
              std::map<unsigned int, double> difference;
              for (unsigned int i = 0; i < support.n_nodes; ++i)
                difference[support.nodes[i]] += support.N[i];
              for (unsigned int i = 0; i < other.n_nodes; ++i)
                difference[other.nodes[i]] -= other.N[i];
              for (const auto &[node, d] : difference)
                continuity = std::max(continuity, std::abs(d));
            }
        }
    }
  mpm_tests::check("some owned cells have hanging vertices",
                   Utilities::MPI::sum(n_hanging_cells, comm) > 0);
  mpm_tests::check("faces to a coarser owned cell were compared",
                   Utilities::MPI::sum(n_faces, comm) > 0);
  mpm_tests::check("sum N = 1 to 1e-14",
                   Utilities::MPI::max(unity, comm) < 1e-14);
  mpm_tests::check("sum N x_i = x to 1e-14",
                   Utilities::MPI::max(reproduction, comm) < 1e-14);
  mpm_tests::check("sum grad N = 0 and sum x_i grad N = I to 1e-13",
                   Utilities::MPI::max(gradient, comm) < 1e-13);
  mpm_tests::check("no support reaches a hanging node",
                   !Utilities::MPI::logical_or(reaches_hanging, comm));
  mpm_tests::check("N is continuous across coarse-fine faces to 1e-14",
                   Utilities::MPI::max(continuity, comm) < 1e-14);
}



template <int dim>
void
check_free_fall()
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const double   g = 9.81;
  ParameterHandler prm;
  // Not on the vertices of the refined cells, where a point's gradients
  // would reach nodes that get no mass.
  mpm_tests::parse_small_scene<dim>(
    prm, mpm_tests::block_in_unit_box<dim>("Gauss"));
  Tensor<1, dim> gravity;
  gravity[dim - 1] = -g;
  mpm_tests::SmallExplicitRun<dim> run(prm, gravity);
  auto &[grid, dirichlet, nodes, basis, materials, points, transfer, timer,
         integrator] = run;

  const types::particle_index n_points = points.n_global_points();
  bool                        hanging_around_points = false;
  const auto [velocity_error, height_error] =
    mpm_tests::free_fall_errors(run, g, [&](const unsigned int n) {
      // The cells with points and the cells next to them, twice; then
      // back.
      if (n == 6 || n == 8)
        grid.adapt([&](const auto &cell) {
          return points.handler().n_particles_in_cell(cell) > 0 ? 1 : 0;
        });
      if (n == 14 || n == 16)
        grid.adapt([](const auto &) { return -1; });
      for (const auto &cell : grid.get_triangulation().active_cell_iterators())
        if (cell->is_locally_owned() &&
            points.handler().n_particles_in_cell(cell) > 0 &&
            grid.cell_geometry(cell->active_cell_index()).n_hanging > 0)
          hanging_around_points = true;
      if (n == 10)
        mpm_tests::check_projection_conserves(
          run, "a projection with hanging nodes");
    });
  mpm_tests::check("points lay in cells with hanging vertices",
                   Utilities::MPI::logical_or(hanging_around_points, comm));
  mpm_tests::check("no point lost", points.n_global_points() == n_points);
  mpm_tests::check("the grid is back to its 4^dim cells",
                   grid.get_triangulation().n_global_active_cells() ==
                     Utilities::fixed_power<dim>(4u));
  mpm_tests::check("free fall: v = -g t_n to 1e-12", velocity_error < 1e-12);
  mpm_tests::check("and y_n = y_0 - g t_n (t_n + dt) / 2 to 1e-12",
                   height_error < 1e-12);
}



template <int dim>
void
check_uniform_stress()
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  ParameterHandler prm;
  mpm_tests::parse_small_scene<dim>(
    prm,
    std::string("subsection Grid\n set Generator = subdivided_hyper_cube\n"
                " set Arguments = 4 : 0 : 1 : true\nend\n"
                "subsection Boundary conditions\n set Slip boundaries = "
                "left, right, bottom, top") +
      (dim == 3 ? ", back, front" : "") +
      "\nend\nsubsection body\n set Shape = box\n" +
      (dim == 2 ? " set Lower corner = 0,0\n set Upper corner = 1,1\n" :
                  " set Lower corner = 0,0,0\n set Upper corner = 1,1,1\n") +
      " set Material = steel\nend\n");
  mpm_tests::SmallExplicitRun<dim> run(prm, Tensor<1, dim>(), [](auto &grid) {
    refine_left_of(grid, 0.5);
  });
  MaterialPoints<dim> &points = run.points;
  using Layout                = PointLayout<dim>;
  SymmetricTensor<2, 3> stress;
  stress[0][0] = -1e6;
  stress[1][1] = -2e6;
  stress[2][2] = -3e6;
  for (auto &particle : points.handler())
    Layout::set_stress(particle.get_properties(), stress);
  // One step of an unbalanced force of the stress on a cell would give a
  // point sigma dt / (rho h) = 2e6 1e-6 / (1000 0.25) = 8e-3 m/s.
  double speed = 0., stress_change = 0.;
  for (unsigned int n = 0; n < 10; ++n)
    {
      run.integrator.step(1e-6);
      points.sort();
      for (const auto &particle : points.handler())
        {
          const ArrayView<const double> p = particle.get_properties();
          speed = std::max(speed, Layout::get_velocity(p).norm());
          stress_change = std::max(
            stress_change, (Layout::get_stress(p) - stress).norm() / 3e6);
        }
    }
  mpm_tests::check("a uniform stress across the coarse-fine interface "
                   "stays at rest: |v| < 1e-13 m/s",
                   Utilities::MPI::max(speed, comm) < 1e-13);
  mpm_tests::check("and uniform, to 1e-13 relative",
                   Utilities::MPI::max(stress_change, comm) < 1e-13);
}



/** The number that follows `before` in `text`, or -1. */
double
number_after(const std::string &text, const std::string &before)
{
  const auto at = text.find(before);
  if (at == std::string::npos)
    return -1.;
  std::istringstream in(text.substr(at + before.size()));
  double             n = -1.;
  in >> n;
  return n;
}



/**
 * The same collapse with part of the material one level finer than the
 * rest: `adaptive` are the settings of the run refined twice everywhere
 * near the material, `fixed` the uniform grid's time series, `screen`
 * what the adaptive run printed.
 */
void
check_finer_levels(const std::string &                   scene,
                   const std::vector<std::string> &      adaptive,
                   mpm_tests::Columns &                  fixed,
                   const std::string &                   screen)
{
  deallog << "--- finer levels in a region, and where material flows"
          << std::endl;
  std::vector<std::string> once = adaptive, region = adaptive,
                           flowing;
  for (auto &setting : once)
    if (setting == "Adaptive grid/Refinement levels=2")
      setting = "Adaptive grid/Refinement levels=1";
  flowing = once;
  region  = once;
  region.insert(region.end(),
                {"Adaptive grid/Finer levels=1",
                 "Adaptive grid/Finer where=region",
                 "Adaptive grid/Finer region/Lower corner=-1, -1",
                 "Adaptive grid/Finer region/Upper corner=1, 1"});
  std::vector<std::string> toe = once;
  toe.insert(toe.end(),
             {"Adaptive grid/Finer levels=1",
              "Adaptive grid/Finer where=region",
              "Adaptive grid/Finer region/Lower corner=0.15, -1",
              "Adaptive grid/Finer region/Upper corner=1, 1"});
  flowing.insert(flowing.end(),
                 {"Adaptive grid/Finer levels=1",
                  "Adaptive grid/Finer where=plastic flow",
                  "Adaptive grid/Finer plastic strain rate=2"});
  std::string once_screen, region_screen, flowing_screen, first_screen,
    toe_screen;
  mpm_tests::run_scene(scene, "output-once", once, &once_screen);
  auto at_toe =
    mpm_tests::run_scene(scene, "output-finer-toe", toe, &toe_screen);
  auto everywhere = mpm_tests::run_scene(
    scene, "output-finer-region", region, &region_screen);
  auto flow = mpm_tests::run_scene(
    scene, "output-finer-flow", flowing, &flowing_screen);
  std::vector<std::string> first = flowing;
  first.push_back("Time stepping/End time=0.03");
  mpm_tests::run_scene(scene, "output-finer-parts", first, &first_screen);
  int  code  = -1;
  auto parts = mpm_tests::run_scene(
    scene, "output-finer-parts", flowing, nullptr, &code, true);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return;

  const std::string at_end = " times; ";
  const double      cells_once =
    number_after(once_screen.substr(once_screen.find(at_end)), at_end),
               cells_flow = number_after(
                 flowing_screen.substr(flowing_screen.find(at_end)), at_end),
               cells_finest =
                 number_after(screen.substr(screen.find(at_end)), at_end),
               cells_toe = number_after(
                 toe_screen.substr(toe_screen.find(at_end)), at_end);
  deallog << "cells at the end: " << cells_once << " refined once, "
          << cells_flow << " with the flowing material once more, "
          << cells_toe << " with the material beyond x = 0.15 m once more, "
          << cells_finest << " refined twice" << std::endl;
  mpm_tests::check("a Finer region over part of the column (x > 0.15 m): "
                   "more cells than the grid refined once at the end, fewer "
                   "than the one refined twice, and its mass kept to 1e-12",
                   cells_once < cells_toe && cells_toe < cells_finest &&
                     std::abs(at_toe["mass"].back() /
                                at_toe["mass"].front() -
                              1.) < 1e-12);
  mpm_tests::check("a Finer region over the whole box gives the time series "
                   "of the grid refined twice (and of the uniform grid) to "
                   "1e-9 of each column's largest value",
                   mpm_tests::largest_difference(fixed, everywhere) < 1e-9);
  mpm_tests::check("refined where the material flows: more cells than the "
                   "grid refined once at the end, fewer than the one refined "
                   "twice",
                   cells_once > 0. && cells_once < cells_flow &&
                     cells_flow < cells_finest);
  mpm_tests::check("its mass stays the mass at the start to 1e-12",
                   std::abs(flow["mass"].back() / flow["mass"].front() - 1.) <
                     1e-12);
  mpm_tests::check("a run continued from a checkpoint repeats it to the "
                   "last digit (each point's plastic strain at the last "
                   "check is saved, and the time of that check)",
                   code == 0 &&
                     mpm_tests::largest_difference(flow, parts) == 0.);
}



void
check_column_collapse()
{
  deallog << "--- granular column collapse" << std::endl;
  const std::string              scene = "../prm/granular_collapse.prm";
  // Fixed steps, so that the first part ends on a step of the whole run.
  const std::vector<std::string> common = {"Time stepping/End time=0.06",
                                           "Time stepping/Time step=5e-5",
                                           "Output/Interval=0"};
  std::vector<std::string> uniform = common, adaptive = common;
  uniform.push_back("Grid/Arguments=160, 24 : 0, 0 : 0.8, 0.12 : true");
  adaptive.push_back("Grid/Arguments=40, 6 : 0, 0 : 0.8, 0.12 : true");
  adaptive.push_back("Adaptive grid/Refinement levels=2");
  adaptive.push_back("Checkpoint/Wall time interval=1e9");
  // On two ranks the load balance repartitions at the start only; after
  // that each adaptation must repartition by the points, as the
  // checkpoint restores the last weights.
  adaptive.push_back("Load balance/Check interval=100000");
  adaptive.push_back("Load balance/Imbalance tolerance=1");
  std::string screen;
  auto fixed = mpm_tests::run_scene(scene, "output-uniform", uniform);
  auto following =
    mpm_tests::run_scene(scene, "output-adaptive", adaptive, &screen);

  std::vector<std::string> first = adaptive;
  first.push_back("Time stepping/End time=0.03");
  std::string first_screen;
  mpm_tests::run_scene(scene, "output-parts", first, &first_screen);
  int  code  = -1;
  auto parts = mpm_tests::run_scene(
    scene, "output-parts", adaptive, nullptr, &code, true);
  check_finer_levels(scene, adaptive, fixed, screen);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    return;

  const double start_cells =
                 number_after(screen, "mpm: adaptive grid, "),
               adaptations_before_stop =
                 number_after(first_screen, "mpm: the grid adapted ");
  deallog << "adaptive grid: " << start_cells << " cells at the start, "
          << "against 3840 uniform" << std::endl;
  mpm_tests::check("the grid that follows the column has fewer than 2/3 of "
                   "the uniform grid's cells",
                   start_cells > 0. && start_cells < 2560.);
  mpm_tests::check("the grid adapted before the checkpoint",
                   adaptations_before_stop >= 1.);
  mpm_tests::check("the time series equals the uniform grid's to 1e-9 of "
                   "each column's largest value",
                   mpm_tests::largest_difference(fixed, following) < 1e-9);
  mpm_tests::check("the continued run exits with 0 and repeats the run made "
                   "in one go to the last digit",
                   code == 0 &&
                     mpm_tests::largest_difference(following, parts) == 0.);
}



void
check_newmark_column()
{
  deallog << "--- cohesive column collapse, Newmark" << std::endl;
  const std::string              scene  = "../prm/column_collapse.prm";
  const std::vector<std::string> common = {
    "Time stepping/Scheme=Newmark",
    "Time stepping/Time step=0.02",
    "Time stepping/End time=0.6",
    "Newmark/Mass matrix=lumped",
    "Newton/Integration=material points"};
  std::vector<std::string> uniform = common, adaptive = common;
  uniform.push_back("Grid/Arguments=40, 12 : 0, 0 : 8, 2.4 : true");
  adaptive.push_back("Grid/Arguments=10, 3 : 0, 0 : 8, 2.4 : true");
  adaptive.push_back("Adaptive grid/Refinement levels=2");
  std::vector<std::string> tight = adaptive;
  tight.push_back("Adaptive grid/Margin=0");
  int  code  = -1;
  auto fixed = mpm_tests::run_scene(scene, "output-newmark-uniform", uniform);
  auto following =
    mpm_tests::run_scene(scene, "output-newmark-adaptive", adaptive);
  auto hanging = mpm_tests::run_scene(
    scene, "output-newmark-margin-0", tight, nullptr, &code);
  mpm_tests::check("Margin = 2: the time series equals the uniform grid's "
                   "to 1e-9 of each column's largest value",
                   mpm_tests::largest_difference(fixed, following) < 1e-9);
  double gap = 0.;
  for (const std::string column : {"centre_of_mass_x", "centre_of_mass_y"})
    gap = std::max(gap,
                   std::abs(hanging[column].back() - fixed[column].back()) /
                     fixed[column].back());
  mpm_tests::check("Margin = 0: the run reaches its end, its centre of mass "
                   "within 1 % of the uniform grid's",
                   code == 0 && hanging["time"].back() > 0.6 - 1e-9 &&
                     gap < 0.01);
}



void
check_obstacle_left_behind()
{
  deallog << "--- a small obstacle the grid coarsens around" << std::endl;
  std::string screen;
  int         exit_code = -1;
  auto csv = mpm_tests::run_scene("scenes/obstacle_left_behind.prm",
                                  "output-obstacle-left-behind",
                                  {},
                                  &screen,
                                  &exit_code);
  mpm_tests::check("the run reaches its end time, 0.3 s",
                   exit_code == 0 && !csv["time"].empty() &&
                     csv["time"].back() > 0.3 - 1e-12);
  // "mpm: the grid adapted N times" (rank 0 prints it, and logs).
  const std::string  said = "the grid adapted ";
  const auto         at   = screen.find(said);
  const unsigned int n_adaptations =
    at == std::string::npos ? 0 : std::stoul(screen.substr(at + said.size()));
  deallog << "grid changes: " << n_adaptations << std::endl;
  mpm_tests::check("the grid adapted during the run", n_adaptations > 0);
}



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  deallog << "dim = 2" << std::endl;
  check_shape_functions<2>();
  check_free_fall<2>();
  check_uniform_stress<2>();
  deallog << "dim = 3" << std::endl;
  check_shape_functions<3>();
  check_free_fall<3>();
  check_uniform_stress<3>();
  check_column_collapse();
  check_newmark_column();
  check_obstacle_left_behind();
}
