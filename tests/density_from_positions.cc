// The density from the point positions, Wieckowski (2004) eqs. 12-13 in
// their Q1 form (NodalDensity, the grid field "Density from positions"
// that the law names), in 2D, 3D and 2D axisymmetric (the body on the axis;
// the density in the r-z plane, from the ring masses over 2 pi x), on one
// or two ranks, with Wieckowski's granular law seeded loose:
// - the grid field's value at every point is, to the last bit, the nodal
//   mass over the occupied nodal volume interpolated, rho_P = sum_i N_i
//   m_i / V_i, with m_i the mass that the nodal projection of the scheme
//   gives the nodes (GridNodes; in axisymmetry the plane masses m / 2 pi x,
//   summed here) and V_i the integrals of N_i over the cells that hold
//   points, summed here;
// - a body of 1000 kg/m3 of a law whose reference density is 1500 starts
//   stress-free at J = 1.5 (volumetric_strain = ln 1.5);
// - on a lattice of points at the centres of a regular subdivision of
//   each cell, rho_P is the lattice's density at every point, those on the
//   body's free surfaces included (the midpoint rule is exact for the
//   bilinear N_i), to round-off; the law then gives no stress (loose);
// - the same lattice compressed uniformly by J = 2^-dim (every point moved
//   to x / 2) gives rho / J at every point, and the law the void-ratio
//   pressure p0 exp((1 + e0)/kappa (1 - rho_ref/rho_P)) to round-off.
// The body lies on the grid's lower faces and ends inside it, so its upper
// faces are free surfaces. A lattice shifted off the cell centres is not
// exact; its range over 49 shifts is printed, not checked
// (doc/architecture.md: at a free surface the density falls where a few
// points reach into an empty cell and rises, up to (n + 1)/n in 1D for n
// points per cell direction, where the last points come close to a node
// whose outer cell is empty).

#include <deal.II/base/mpi.h>

#include <mpm/assembly/grid_transfer.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>
#include <mpm/materials/wieckowski_granular.h>

#include <cmath>

#include "small_scene.h"
#include "tests.h"

using namespace dealii;
using namespace mpm;

template <int dim>
void
test(const bool axisymmetric = false)
{
  deallog << "dim = " << dim << (axisymmetric ? ", axisymmetric" : "")
          << std::endl;
  const MPI_Comm comm   = MPI_COMM_WORLD;
  using Layout          = PointLayout<dim>;
  const double rho_ref  = 1500., rho = 1000.;
  const double p0 = 600., compression_ratio = (1. + 0.9) / 0.02;

  ParameterHandler prm;
  mpm_tests::parse_small_scene<dim>(
    prm,
    std::string("subsection Grid\n set Generator = subdivided_hyper_cube\n"
                " set Arguments = 8 : 0 : 1 : false\n") +
    (axisymmetric ? " set Geometry = axisymmetric\n" : "") +
    std::string("end\n"
                "subsection material\n set Model = Wieckowski granular\n"
                " set Density = 1500\n"
                " subsection Wieckowski granular\n"
                "  set Density from positions = true\n end\nend\n"
                "subsection body\n set Shape = box\n set Density = 1000\n") +
    (dim == 2 ? " set Lower corner = 0,0\n set Upper corner = 0.5,0.5\n" :
                " set Lower corner = 0,0,0\n set Upper corner = 0.5,0.5,0.5\n") +
    " set Material = steel\n set Points per cell direction = 2\nend\n");

  Grid<dim> grid(prm, comm);
  grid.create();
  GridNodes<dim> nodes(grid);
  nodes.setup();
  GridBasis<dim>           basis(grid);
  DirichletConditions<dim> dirichlet(prm, grid);
  dirichlet.setup();
  std::vector<std::unique_ptr<Material>> materials;
  MaterialPoints<dim> points(grid, {"plastic_strain", "volumetric_strain"});
  mpm_tests::seed_small_scene(prm, grid, materials, points);
  const Material &law = *materials[0];

  double seeded_stress = 0., seeded_strain_error = 0.;
  for (const auto &particle : points.handler())
    {
      const ArrayView<const double> p = particle.get_properties();
      seeded_stress = std::max(seeded_stress, Layout::get_stress(p).norm());
      seeded_strain_error =
        std::max(seeded_strain_error,
                 std::abs(p[Layout::internal_variables + 1] -
                          std::log(rho_ref / rho)));
    }
  mpm_tests::check("a loose body (1000 against 1500 kg/m3) is seeded "
                   "stress-free at volumetric_strain = ln 1.5",
                   Utilities::MPI::max(seeded_stress, comm) == 0. &&
                     Utilities::MPI::max(seeded_strain_error, comm) < 1e-15);

  GridTransfer<dim> transfer(points, basis, nodes, {&dirichlet},
                             Tensor<1, dim>());
  transfer.use_grid_fields(materials);

  // rho_P = sum_i N_i m_i / V_i, summed here from the nodes' masses (the
  // plane masses in axisymmetry) and the occupied cells' integrals.
  auto expected_density = [&]() {
    // Held by the returned function; a copy of a vector would not keep its
    // ghost values.
    auto volume_vector =
      std::make_shared<LinearAlgebra::distributed::Vector<double>>(
        grid.node_partitioner());
    auto plane_mass_vector =
      std::make_shared<LinearAlgebra::distributed::Vector<double>>(
        grid.node_partitioner());
    auto &volume     = *volume_vector;
    auto &plane_mass = *plane_mass_vector;
    Support<dim> integrals;
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned() &&
          points.handler().n_particles_in_cell(cell) > 0)
        {
          basis.cell_integrals(cell->active_cell_index(), integrals);
          for (unsigned int i = 0; i < integrals.n_nodes; ++i)
            volume.local_element(integrals.nodes[i]) += integrals.N[i];
        }
    transfer.for_each_point([&](auto &particle, const Support<dim> &support) {
      const double m = particle->get_properties()[Layout::mass] /
                       grid.geometry().out_of_plane_measure(
                         particle->get_location());
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        plane_mass.local_element(support.nodes[i]) += support.N[i] * m;
    });
    for (auto *vector : {&volume, &plane_mass})
      {
        vector->compress(VectorOperation::add);
        vector->update_ghost_values();
      }
    return [&nodes, axisymmetric, volume_vector, plane_mass_vector](
             const Support<dim> &support) {
      double density = 0.;
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          const unsigned int node   = support.nodes[i];
          const double       volume = volume_vector->local_element(node);
          if (volume > 0.)
            density += support.N[i] *
                       (axisymmetric ? plane_mass_vector->local_element(node) :
                                       nodes.mass_at(node)) /
                       volume;
        }
      return density;
    };
  };

  // The largest |rho_P / expected - 1| and the largest |sigma + p I| / p
  // of the law's update at rho_P, over all points; `bitwise` stays true
  // while rho_P is the nodes' sum to the last bit.
  bool bitwise = true;
  auto measure = [&](const double expected, double &density_error,
                     double &stress_error, double &low, double &high) {
    transfer.project_mass_momentum(false);
    const auto reference = expected_density();
    density_error = stress_error = 0.;
    low                          = 1e300;
    high                         = 0.;
    transfer.for_each_point([&](auto &particle, const Support<dim> &support) {
      StepKinematics from_grid;
      transfer.read_grid_fields(0, support, from_grid);
      const double rho_P = from_grid.grid_fields[0];
      if (rho_P != reference(support))
        bitwise = false;
      density_error = std::max(density_error, std::abs(rho_P / expected - 1.));
      low           = std::min(low, rho_P);
      high          = std::max(high, rho_P);
      StepKinematics k;
      k.dt    = 1e-4;
      k.F_old = k.F_new = Tensor<2, 3>(unit_symmetric_tensor<3>());
      k.grid_fields[0]  = rho_P;
      SymmetricTensor<2, 3> stress;
      std::vector<double>   internal(2, 0.);
      law.update_stress(k, stress, ArrayView<double>(internal.data(), 2));
      const double J = rho_ref / rho_P;
      const double p_law =
        J > 1. + 13.8 / compression_ratio ?
          0. :
          p0 * std::exp(compression_ratio * (1. - J));
      stress_error = std::max(stress_error,
                              (stress + p_law * unit_symmetric_tensor<3>())
                                  .norm() /
                                std::max(p_law, 1.));
    });
    density_error = Utilities::MPI::max(density_error, comm);
    stress_error  = Utilities::MPI::max(stress_error, comm);
    low           = Utilities::MPI::min(low, comm);
    high          = Utilities::MPI::max(high, comm);
  };

  double density_error, stress_error, low, high;
  measure(rho, density_error, stress_error, low, high);
  mpm_tests::check("lattice: rho_P = 1000 at every point, free surfaces "
                   "included, to 1e-12",
                   density_error < 1e-12);
  mpm_tests::check("lattice: the loose fill carries no stress",
                   stress_error == 0.);

  auto move_points = [&](const auto &motion) {
    for (auto &particle : points.handler())
      particle.set_location(motion(particle.get_location()));
    points.sort();
  };
  // Halving the radius also halves the rings' hoop stretch.
  move_points([](const Point<dim> &x) { return Point<dim>(x / 2.); });
  const unsigned int inverse_J  = 1u << (axisymmetric ? dim + 1 : dim);
  const double       compressed = rho * inverse_J;
  measure(compressed, density_error, stress_error, low, high);
  deallog << "compressed by J = 1/" << inverse_J << ": rho_P in [" << low
          << ", " << high << "]" << std::endl;
  mpm_tests::check("compressed by J: rho_P = rho / J at every point to "
                   "1e-12",
                   density_error < 1e-12);
  mpm_tests::check("compressed: the law's pressure is p0 exp((1 + e0)/kappa "
                   "(1 - rho_ref/rho_P)) to 1e-9",
                   stress_error < 1e-9);

  // Back to the seeded lattice, then off the cell centres: shifts of
  // (a, b) h / 7 in x and y, a, b = 0..6.
  move_points([](const Point<dim> &x) { return Point<dim>(2. * x); });
  double lowest = rho, highest = rho, a_done = 0., b_done = 0.;
  for (unsigned int a = 0; a < 7; ++a)
    for (unsigned int b = 0; b < 7; ++b)
      {
        const double da = a / 7. / 8 - a_done, db = b / 7. / 8 - b_done;
        a_done += da;
        b_done += db;
        move_points([da, db](const Point<dim> &x) {
          Point<dim> y = x;
          y[0] += da;
          y[1] += db;
          return y;
        });
        measure(rho, density_error, stress_error, low, high);
        lowest  = std::min(lowest, low);
        highest = std::max(highest, high);
      }
  deallog << "lattice shifted by (a, b) h/7, a, b = 0..6: rho_P in ["
          << lowest << ", " << highest << "]" << std::endl;
  mpm_tests::check("at every point of every lattice, the grid field is "
                   "sum_i N_i m_i / V_i of the nodes' masses, to the last bit",
                   !Utilities::MPI::logical_or(!bitwise, comm));
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  test<2>();
  test<3>();
  test<2>(true);
}
