// A grid, one box body and one material named "steel", described by
// parameter text: what the tests that build the library's pieces by hand
// (without the Simulator) share.
#ifndef mpm_tests_small_scene_h
#define mpm_tests_small_scene_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/assembly/grid_nodes.h>
#include <mpm/bodies/body.h>
#include <mpm/bodies/point_seeder.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>

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
} // namespace mpm_tests

#endif
