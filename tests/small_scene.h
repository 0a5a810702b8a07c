// A grid, one box body and one material named "steel", described by
// parameter text: what the tests that build the library's pieces by hand
// (without the Simulator) share.
#ifndef mpm_tests_small_scene_h
#define mpm_tests_small_scene_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/base/timer.h>

#include <mpm/assembly/grid_nodes.h>
#include <mpm/assembly/grid_transfer.h>
#include <mpm/bodies/body.h>
#include <mpm/bodies/point_seeder.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>
#include <mpm/time/explicit_integrator.h>

#include <functional>
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include "tests.h"

namespace mpm_tests
{
  /**
   * Declare `Grid`, `Boundary conditions`, a body in `body` and a
   * material in `material`, and parse `text`.
   */
  template <int dim>
  void
  parse_small_scene(dealii::ParameterHandler &prm, const std::string &text)
  {
    mpm::Grid<dim>::declare_parameters(prm);
    mpm::DirichletConditions<dim>::declare_parameters(prm);
    prm.enter_subsection("body");
    mpm::Body<dim>::declare_parameters(prm);
    prm.leave_subsection();
    prm.enter_subsection("material");
    mpm::Material::declare_parameters(prm);
    prm.leave_subsection();
    prm.parse_input_from_string(text);
  }

  /**
   * The text of a unit square (cube) of 4^dim cells holding a steel box at
   * x, (y,) in [0.3, 0.7] and at heights [0.5, 0.9], its points placed by
   * `placement` (Bodies' Point placement).
   */
  template <int dim>
  std::string
  block_in_unit_box(const std::string &placement = "centres")
  {
    return std::string(
             "subsection Grid\n set Generator = subdivided_hyper_cube\n"
             " set Arguments = 4 : 0 : 1 : true\nend\n"
             "subsection body\n set Shape = box\n") +
           (dim == 2 ?
              " set Lower corner = 0.3,0.5\n set Upper corner = 0.7,0.9\n" :
              " set Lower corner = 0.3,0.3,0.5\n"
              " set Upper corner = 0.7,0.7,0.9\n") +
           " set Point placement = " + placement +
           "\n set Material = steel\nend\n";
  }

  /** Build the material "steel" and seed the body into `points`. */
  template <int dim>
  void
  seed_small_scene(dealii::ParameterHandler &                    prm,
                   const mpm::Grid<dim> &                        grid,
                   std::vector<std::unique_ptr<mpm::Material>> &materials,
                   mpm::MaterialPoints<dim> &                    points)
  {
    prm.enter_subsection("material");
    materials.push_back(mpm::Material::create(prm, "steel", "material"));
    prm.leave_subsection();
    std::vector<mpm::Body<dim>> bodies;
    prm.enter_subsection("body");
    bodies.emplace_back(prm, "body", "body", std::vector<std::string>{"steel"});
    prm.leave_subsection();
    mpm::PointSeeder<dim> seeder(grid);
    seeder.release_due(bodies, materials, points, 0., 0.);
  }
  /**
   * The total mass and momentum that the last projection put on the
   * nodes, summed over owned nodes (so a node shared by ranks counts once)
   * and over ranks.
   */
  template <int dim>
  std::pair<double, dealii::Tensor<1, dim>>
  grid_mass_and_momentum(const mpm::Grid<dim> &     grid,
                         const mpm::GridNodes<dim> &nodes)
  {
    using NodalLayout = typename mpm::GridNodes<dim>::NodalLayout;
    double                  mass = 0.;
    dealii::Tensor<1, dim> momentum;
    for (unsigned int node = 0;
         node < grid.node_partitioner()->locally_owned_size();
         ++node)
      {
        const double *v = nodes.values_of(node);
        mass += v[NodalLayout::mass];
        for (unsigned int d = 0; d < dim; ++d)
          momentum[d] += v[NodalLayout::velocity + d];
      }
    const MPI_Comm comm = grid.get_communicator();
    return {dealii::Utilities::MPI::sum(mass, comm),
            dealii::Utilities::MPI::sum(momentum, comm)};
  }

  /**
   * The small scene of `prm` ready for explicit MUSL steps: the grid
   * (created, then changed by `change_grid` before the points are seeded),
   * its Dirichlet conditions, nodal storage, Q1 basis, the seeded points,
   * the transfer with `gravity` and the integrator.
   */
  template <int dim>
  struct SmallExplicitRun
  {
    SmallExplicitRun(
      dealii::ParameterHandler &                    prm,
      const dealii::Tensor<1, dim> &                gravity,
      const std::function<void(mpm::Grid<dim> &)> &change_grid = {})
      : grid(prm, MPI_COMM_WORLD)
      , dirichlet(prm, created(grid, change_grid))
      , nodes(grid)
      , basis(grid)
      , points(grid, {})
      , transfer(points, basis, nodes, {&dirichlet}, gravity)
      , timer(MPI_COMM_WORLD,
              dealii::deallog.get_console(),
              dealii::TimerOutput::never,
              dealii::TimerOutput::wall_times)
      , integrator(transfer,
                   materials,
                   mpm::ExplicitIntegrator<dim>::Scheme::MUSL,
                   0.,
                   false,
                   grid,
                   timer)
    {
      dirichlet.setup();
      nodes.setup();
      seed_small_scene(prm, grid, materials, points);
    }

    static mpm::Grid<dim> &
    created(mpm::Grid<dim> &                              grid,
            const std::function<void(mpm::Grid<dim> &)> &change_grid)
    {
      grid.create();
      if (change_grid)
        change_grid(grid);
      return grid;
    }

    mpm::Grid<dim>                              grid;
    mpm::DirichletConditions<dim>               dirichlet;
    mpm::GridNodes<dim>                         nodes;
    mpm::GridBasis<dim>                         basis;
    std::vector<std::unique_ptr<mpm::Material>> materials;
    mpm::MaterialPoints<dim>                    points;
    mpm::GridTransfer<dim>                      transfer;
    dealii::TimerOutput                         timer;
    mpm::ExplicitIntegrator<dim>                integrator;
  };

  /**
   * Steps n = 1 ... 20 of `run`'s block in free fall under gravity g with
   * dt = 1e-3, `before_step(n)` called before each: the largest error over
   * the steps and points of MUSL's exact discrete solution, v = -g t_n for
   * every point and y_0 - g t_n (t_n + dt) / 2 for the centre of mass.
   */
  template <int dim>
  std::pair<double, double>
  free_fall_errors(SmallExplicitRun<dim> &                   run,
                   const double                              g,
                   const std::function<void(unsigned int)> &before_step)
  {
    using Layout        = mpm::PointLayout<dim>;
    const double   dt   = 1e-3;
    const MPI_Comm comm = MPI_COMM_WORLD;
    const auto     centre_height = [&]() {
      double sum = 0.;
      for (const auto &particle : run.points.handler())
        sum += particle.get_location()[dim - 1];
      return dealii::Utilities::MPI::sum(sum, comm) /
             run.points.n_global_points();
    };
    const double y0             = centre_height();
    double       velocity_error = 0., height_error = 0.;
    for (unsigned int n = 1; n <= 20; ++n)
      {
        before_step(n);
        run.integrator.step(dt);
        run.points.sort();
        const double t = n * dt;
        for (const auto &particle : run.points.handler())
          velocity_error = std::max(
            velocity_error,
            std::abs(particle.get_properties()[Layout::velocity + dim - 1] +
                     g * t));
        height_error =
          std::max(height_error,
                   std::abs(centre_height() - (y0 - g * t * (t + dt) / 2.)));
      }
    return {dealii::Utilities::MPI::max(velocity_error, comm), height_error};
  }

  /**
   * Project `run`'s points to the grid once and check, as `what` conserves
   * mass and momentum to 1e-13.
   */
  template <int dim>
  void
  check_projection_conserves(SmallExplicitRun<dim> &run,
                             const std::string &    what)
  {
    using Layout                   = mpm::PointLayout<dim>;
    const MPI_Comm         comm    = MPI_COMM_WORLD;
    double                 mass    = 0.;
    dealii::Tensor<1, dim> momentum;
    for (const auto &particle : run.points.handler())
      {
        const dealii::ArrayView<const double> p = particle.get_properties();
        mass += p[Layout::mass];
        momentum += p[Layout::mass] * Layout::get_velocity(p);
      }
    mass     = dealii::Utilities::MPI::sum(mass, comm);
    momentum = dealii::Utilities::MPI::sum(momentum, comm);
    run.transfer.project_mass_momentum(false);
    const auto [grid_mass, grid_momentum] =
      grid_mass_and_momentum(run.grid, run.nodes);
    check(what + " conserves mass to 1e-13",
          std::abs(grid_mass - mass) < 1e-13 * mass);
    check("and momentum to 1e-13",
          (grid_momentum - momentum).norm() < 1e-13 * momentum.norm());
  }
} // namespace mpm_tests

#endif
