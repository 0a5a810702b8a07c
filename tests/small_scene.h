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
      , points(grid, {}, false, false)
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
} // namespace mpm_tests

#endif
