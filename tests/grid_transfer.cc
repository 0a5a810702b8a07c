// The grid bases and the point-grid transfer, on one or two ranks: Q1 on
// distorted 2D and 3D grids, and uGIMP, cpGIMP and quadratic B-splines on
// grids of equal boxes (longer in x than in y):
// - at random points of every cell, and at points next to every grid face,
//   shape functions sum to 1, gradients to 0, and linear fields are
//   reproduced (sum N x_i = x, sum x_i (x) grad N = I); gradients match
//   finite differences of N (GIMP: of the domain-averaged N, whose
//   derivative is the averaged gradient; the domain reaches beyond the
//   grid next to its faces);
// - the smooth kinds reach at most 3^dim nodes, none of them negative for
//   B-splines, and the B-spline cell integrals sum to the grid's volume;
// - seeded points fill the domain's volume;
// - one projection of random point masses and momenta to the grid conserves
//   mass and momentum, and so does interpolating the nodal velocities back
//   (across ranks, through ghost nodes of ghost cells for the smooth kinds).
// All checks are against exact identities, so the tolerances are round-off.

#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>

#include <mpm/assembly/grid_transfer.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>

#include <cmath>
#include <random>

#include "small_scene.h"
#include "tests.h"

using namespace dealii;
using namespace mpm;

template <int dim>
void
test(const GridShapeFunctions kind)
{
  const bool linear = kind == GridShapeFunctions::linear;
  deallog << "dim = " << dim
          << ", shape functions: " << GridBasis<dim>::name(kind) << std::endl;
  const MPI_Comm comm = MPI_COMM_WORLD;

  // Q1 on a distorted grid; the smooth kinds on boxes of 0.2 x 0.25
  // (x 0.25).
  ParameterHandler prm;
  mpm_tests::parse_small_scene<dim>(
    prm,
    std::string("subsection Grid\n") +
      (linear ? " set Generator = subdivided_hyper_cube\n"
                " set Arguments = 4 : 0 : 1 : false\n" :
       dim == 2 ? " set Arguments = 5, 4 : 0, 0 : 1, 1 : true\n" :
                  " set Arguments = 5, 4, 4 : 0, 0, 0 : 1, 1, 1 : true\n") +
      "end\nsubsection body\n set Shape = box\n" +
      (dim == 2 ? " set Lower corner = 0,0\n set Upper corner = 1,1\n" :
                  " set Lower corner = 0,0,0\n set Upper corner = 1,1,1\n") +
      " set Material = steel\n set Points per cell direction = 3\nend\n");

  Grid<dim> grid(prm, comm);
  grid.create();
  if (linear)
    grid.transform(&mpm_tests::distort<dim>);
  const auto &tria = grid.get_triangulation();

  GridNodes<dim> nodes(grid);
  nodes.setup();
  GridBasis<dim>           basis(grid, kind);
  DirichletConditions<dim> dirichlet(prm, grid);
  dirichlet.setup();
  MappingQ<dim> mapping(1);
  deallog << "grid is cartesian: " << grid.is_cartesian() << std::endl;

  // A point seeded at 2 per cell direction (GIMP's domain is half its
  // size), stretched by F = diag(1.3, 0.8, 1.1) (cpGIMP's domain follows).
  using Layout = PointLayout<dim>;
  std::vector<double> properties(Layout::n_properties(0), 0.);
  for (unsigned int d = 0; d < dim; ++d)
    {
      properties[Layout::reference_size + d] = d == 0 ? 0.1 : 0.125;
      properties[Layout::deformation_gradient + d * dim + d] =
        d == 0 ? 1.3 : d == 1 ? 0.8 : 1.1;
    }
  const ArrayView<const double> p(properties);

  // Basis identities at random points of every locally owned cell, and at
  // points 1e-3 of a cell from each of its faces.
  {
    std::mt19937                           rng(42);
    std::uniform_real_distribution<double> unit(0., 1.);
    double       partition_error = 0., gradient_sum_error = 0.;
    double       position_error = 0., linear_gradient_error = 0.;
    double       fd_error = 0., smallest_N = 0.;
    unsigned int most_nodes = 0;
    Support<dim> s, s_plus, s_minus;
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned int k = 0; k < 5 + 2 * dim; ++k)
          {
            Point<dim> xi;
            for (unsigned int d = 0; d < dim; ++d)
              xi[d] = unit(rng);
            if (k >= 5)
              xi[(k - 5) / 2] = (k - 5) % 2 == 0 ? 1e-3 : 1. - 1e-3;
            basis.evaluate(cell->active_cell_index(), xi, p, s);
            const Point<dim> x =
              mapping.transform_unit_to_real_cell(cell, xi);
            double         sum_N = 0.;
            Tensor<1, dim> sum_grad;
            Point<dim>     x_from_N;
            Tensor<2, dim> identity_from_grad;
            for (unsigned int i = 0; i < s.n_nodes; ++i)
              {
                const Point<dim> &x_i = grid.node_position(s.nodes[i]);
                sum_N += s.N[i];
                sum_grad += s.grad_N[i];
                x_from_N += s.N[i] * x_i;
                identity_from_grad +=
                  outer_product(Tensor<1, dim>(x_i), s.grad_N[i]);
                smallest_N = std::min(smallest_N, s.N[i]);
              }
            most_nodes = std::max(most_nodes, s.n_nodes);
            partition_error    = std::max(partition_error, std::abs(sum_N - 1.));
            gradient_sum_error = std::max(gradient_sum_error, sum_grad.norm());
            position_error = std::max(position_error, (x_from_N - x).norm());
            linear_gradient_error =
              std::max(linear_gradient_error,
                       (identity_from_grad -
                        Tensor<2, dim>(unit_symmetric_tensor<dim>()))
                         .norm());

            // Central differences of N along each reference direction
            // (the supports list the same nodes in the same order).
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double eps     = 1e-6;
                Point<dim>   xi_plus = xi, xi_minus = xi;
                xi_plus[d] += eps;
                xi_minus[d] -= eps;
                basis.evaluate(cell->active_cell_index(), xi_plus, p, s_plus);
                basis.evaluate(cell->active_cell_index(), xi_minus, p, s_minus);
                const Tensor<1, dim> dx =
                  mapping.transform_unit_to_real_cell(cell, xi_plus) -
                  mapping.transform_unit_to_real_cell(cell, xi_minus);
                const auto value_of = [](const Support<dim> &support,
                                         const unsigned int  node) {
                  for (unsigned int j = 0; j < support.n_nodes; ++j)
                    if (support.nodes[j] == node)
                      return support.N[j];
                  return 0.;
                };
                for (unsigned int i = 0; i < s.n_nodes; ++i)
                  fd_error = std::max(
                    fd_error,
                    std::abs(value_of(s_plus, s.nodes[i]) -
                             value_of(s_minus, s.nodes[i]) -
                             s.grad_N[i] * dx) /
                      dx.norm());
              }
          }
    partition_error    = Utilities::MPI::max(partition_error, comm);
    gradient_sum_error = Utilities::MPI::max(gradient_sum_error, comm);
    position_error     = Utilities::MPI::max(position_error, comm);
    linear_gradient_error = Utilities::MPI::max(linear_gradient_error, comm);
    fd_error              = Utilities::MPI::max(fd_error, comm);
    smallest_N            = Utilities::MPI::min(smallest_N, comm);
    most_nodes            = Utilities::MPI::max(most_nodes, comm);
    mpm_tests::check("sum N = 1 to 1e-13", partition_error < 1e-13);
    mpm_tests::check("sum grad N = 0 to 1e-11", gradient_sum_error < 1e-11);
    mpm_tests::check("sum N x_i = x to 1e-13", position_error < 1e-13);
    mpm_tests::check("sum x_i (x) grad N = I to 1e-12",
                     linear_gradient_error < 1e-12);
    mpm_tests::check("grad N matches finite differences to 1e-6",
                     fd_error < 1e-6);
    if (!linear)
      mpm_tests::check("at most 3^dim nodes per point",
                       most_nodes <= Utilities::pow(3, dim));
    if (kind == GridShapeFunctions::quadratic_bspline)
      mpm_tests::check("no negative B-spline value", smallest_N >= 0.);

    // The cell integrals of all functions sum to the grid's volume, and
    // those of every node to h^dim where its functions are whole (a node
    // two cells or more from every face).
    if (!linear)
      {
        Support<dim>     integrals;
        std::map<unsigned int, double> per_node;
        double           total = 0.;
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              basis.cell_integrals(cell->active_cell_index(), integrals);
              for (unsigned int i = 0; i < integrals.n_nodes; ++i)
                {
                  total += integrals.N[i];
                  per_node[integrals.nodes[i]] += integrals.N[i];
                }
            }
        total = Utilities::MPI::sum(total, comm);
        mpm_tests::check("cell integrals sum to the volume to 1e-13",
                         std::abs(total - 1.) < 1e-13);
        if (Utilities::MPI::n_mpi_processes(comm) == 1)
          {
            const double cell_volume = dim == 2 ? 0.2 * 0.25 : 0.2 * 0.25 * 0.25;
            double       error       = 0.;
            for (const auto &[node, integral] : per_node)
              {
                const Point<dim> &x     = grid.node_position(node);
                bool              whole = true;
                const double      h[3]  = {0.2, 0.25, 0.25};
                for (unsigned int d = 0; d < dim; ++d)
                  whole = whole && x[d] > 1.5 * h[d] && x[d] < 1. - 1.5 * h[d];
                if (whole)
                  error = std::max(error, std::abs(integral - cell_volume));
              }
            mpm_tests::check("interior nodal volumes are h^dim to 1e-13",
                             error < 1e-13 * cell_volume);
          }
      }
  }

  // Projection of random masses and momenta, and back.
  {
    std::vector<std::unique_ptr<Material>> materials;
    MaterialPoints<dim>                    points(grid, {});
    mpm_tests::seed_small_scene(prm, grid, materials, points);
    // Masses and velocities from the point id, the same on any number of
    // ranks.
    double         point_mass = 0.;
    Tensor<1, dim> point_momentum;
    for (auto &particle : points.handler())
      {
        std::mt19937                           rng(particle.get_id());
        std::uniform_real_distribution<double> value(0.5, 1.5);
        const ArrayView<double>                p = particle.get_properties();
        p[Layout::mass]                          = value(rng);
        for (unsigned int d = 0; d < dim; ++d)
          p[Layout::velocity + d] = value(rng) - 1.;
        point_mass += p[Layout::mass];
        point_momentum += p[Layout::mass] * Layout::get_velocity(p);
      }
    point_mass = Utilities::MPI::sum(point_mass, comm);

    // Point volumes fill the domain: the midpoint rule of each sub-cell is
    // exact for bilinear cells and boxes, and close for trilinear ones.
    double volume = 0.;
    for (const auto &particle : points.handler())
      volume += particle.get_properties()[Layout::reference_volume];
    volume = Utilities::MPI::sum(volume, comm);
    if (dim == 2 || !linear)
      mpm_tests::check("seeded volume = domain volume to 1e-12",
                       std::abs(volume - 1.) < 1e-12);
    else
      mpm_tests::check("seeded volume = domain volume to 1e-3",
                       std::abs(volume - 1.) < 1e-3);
    point_momentum = Utilities::MPI::sum(point_momentum, comm);

    GridTransfer<dim> transfer(points,
                               basis,
                               nodes,
                               {&dirichlet},
                               Tensor<1, dim>());
    transfer.project_mass_momentum(false);

    const auto [grid_mass, grid_momentum] =
      mpm_tests::grid_mass_and_momentum(grid, nodes);
    mpm_tests::check("P2G conserves mass to 1e-13 (relative)",
                     std::abs(grid_mass - point_mass) < 1e-13 * point_mass);
    mpm_tests::check("P2G conserves momentum to 1e-13 (relative)",
                     (grid_momentum - point_momentum).norm() <
                       1e-13 * point_mass);

    // Back to the points: V_p = sum N v_i conserves momentum.
    transfer.compute_nodal_velocity();
    Tensor<1, dim> returned_momentum;
    transfer.for_each_point([&](auto &particle, const Support<dim> &support) {
      returned_momentum +=
        particle->get_properties()[Layout::mass] *
        transfer.interpolate(support,
                             0,
                             GridNodes<dim>::NodalLayout::velocity);
    });
    returned_momentum = Utilities::MPI::sum(returned_momentum, comm);
    mpm_tests::check("G2P of nodal velocities conserves momentum to 1e-13",
                     (returned_momentum - point_momentum).norm() <
                       1e-13 * point_mass);
    deallog << "points: " << points.n_global_points() << std::endl;
  }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  for (const GridShapeFunctions kind : {GridShapeFunctions::linear,
                                        GridShapeFunctions::uGIMP,
                                        GridShapeFunctions::cpGIMP,
                                        GridShapeFunctions::quadratic_bspline})
    {
      test<2>(kind);
      test<3>(kind);
    }
}
