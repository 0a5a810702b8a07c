// The explicit schemes' steps towards the consistent mass, on one and two
// ranks: the corrected velocity projection (Time stepping/Velocity
// projection = corrected) and the blended mass (Time stepping/Mass matrix
// = blended).
// - the round trip every explicit step makes: nodal velocities w
//   interpolated to the points and projected back. The lumped projection
//   returns M_L^-1 M_C w, which differs from w by O(h^2); one Jacobi step
//   towards the consistent mass returns w - (I - M_L^-1 M_C)^2 w, which
//   differs by O(h^4). Checked with w = (1 + cos(pi x) cos(pi y),
//   2 + cos(pi x) + cos(pi y)) on a unit square filled with 2 x 2 Gauss
//   points per cell (w has no slope across the edges), at the nodes in
//   [3/8, 5/8]^2 (three cells from the edges on the coarsest grid: the
//   edges spoil the order two nodes deep), on 8, 16 and 32 cells a side:
//   the lumped error falls with a rate between 1.8 and 2.2, the corrected
//   one above 3.6. The sum of m_i v_i equals that of m_p v_p to 1e-13.
// - the blended mass keeps momentum: a block with a varying stress under
//   gravity, away from the walls, gets sum m_i a_i = sum m_p g to 1e-13 of
//   the internal forces' size; and its free fall stays exact (the nodal
//   accelerations are all g, which the step leaves as they are). A block
//   on a fixed floor and against a slip wall: the floor's nodes stay at
//   rest and the wall's slide along it only. The elastic block of
//   scenes/friction_block.prm (MUSL, pure PIC) on a Coulomb floor with
//   gravity tilted by 30 degrees: with mu = 0.2 its centre of mass
//   accelerates as the rigid block's g (sin 30 - mu cos 30) within 1 %,
//   with mu = 0.7 it sticks (below 1e-4 m), the floor's force stays in
//   Coulomb's cone (1e-12 of the weight), and the momentum changes by the
//   impulse of gravity and that force (1e-9), as tests/friction_walls
//   checks with the lumped mass.
// - the vibrating bar of benchmarks.md section 7 on 16 cells, USF with CFL
//   0.1: its period against that of the lumped-mass finite-element chain
//   of the same cells, T x / sin(x), x = beta_1 h / 2 (the eigenvector is
//   sin(beta_1 x_i) at the nodes, the half mass at the free end included;
//   the points integrate the constant strain of each cell exactly), which
//   is what a lumped-mass grid can do at best. Corrected within 1e-4;
//   the lumped projection is 9e-4 long and must miss by more than 5e-4,
//   which shows the check tells the two apart. The centre-of-mass velocity
//   v0 cos(omega_1 t) / (beta_1 L) within 1 % of its amplitude over 40 s
//   (the lumped projection: 2.4 %). With the blended mass as well, the
//   period is the exact one, 2 pi / omega_1, within 1e-4 (the lumped
//   mass's chain is 4e-4 long, and the corrected run must miss the exact
//   period by more than 3e-4).
// - the same bar with uGIMP, USF, CFL 0.1, the corrected projection and
//   the blended mass: within 1 % of the amplitude on 16, 32 and 64 cells
//   (Q1 crosses cells on 64 and misses by 15 %; without the blended mass
//   uGIMP misses on 16 cells, 1.1 %).

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>

#include "small_scene.h"

using namespace dealii;

namespace
{
  constexpr unsigned int dim = 2;
  using NodalLayout          = mpm::GridNodes<dim>::NodalLayout;
  using Layout               = mpm::PointLayout<dim>;

  Tensor<1, dim>
  smooth_field(const Point<dim> &x)
  {
    const double cx = std::cos(numbers::PI * x[0]),
                 cy = std::cos(numbers::PI * x[1]);
    return Tensor<1, dim>({1. + cx * cy, 2. + cx + cy});
  }

  /**
   * The largest error of the round trip w -> points -> nodes at the nodes
   * in [3/8, 5/8]^2, lumped and corrected, on n x n
   * cells; and whether each projection kept the momentum to 1e-13.
   */
  std::array<double, 2>
  round_trip_errors(const unsigned int n, bool &momentum_kept)
  {
    ParameterHandler prm;
    mpm_tests::parse_small_scene<dim>(
      prm,
      "subsection Grid\n set Generator = subdivided_hyper_cube\n"
      " set Arguments = " +
        std::to_string(n) +
        " : 0 : 1 : true\nend\n"
        "subsection body\n set Shape = box\n"
        " set Lower corner = 0, 0\n set Upper corner = 1, 1\n"
        " set Point placement = Gauss\n set Material = steel\nend\n");
    mpm_tests::SmallExplicitRun<dim> run(prm, Tensor<1, dim>());
    run.transfer.for_each_point([&](auto &particle, const auto &support) {
      Tensor<1, dim> v;
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        v += support.N[i] *
             smooth_field(run.grid.node_position(support.nodes[i]));
      for (unsigned int d = 0; d < dim; ++d)
        particle->get_properties()[Layout::velocity + d] = v[d];
    });
    Tensor<1, dim> point_momentum;
    for (const auto &particle : run.points.handler())
      point_momentum += particle.get_properties()[Layout::mass] *
                        Layout::get_velocity(particle.get_properties());
    point_momentum = Utilities::MPI::sum(point_momentum, MPI_COMM_WORLD);

    std::array<double, 2> errors;
    for (unsigned int corrected = 0; corrected < 2; ++corrected)
      {
        if (corrected)
          run.transfer.enable_corrected_velocity_projection();
        run.transfer.project_mass_momentum(false);
        run.transfer.compute_nodal_velocity(false);
        double         error = 0.;
        Tensor<1, dim> grid_momentum;
        for (const unsigned int node : run.nodes.slots_to_solve())
          {
            const double *    v = run.nodes.values_of(node);
            const Point<dim> &x = run.grid.node_position(node);
            Tensor<1, dim>    velocity;
            for (unsigned int d = 0; d < dim; ++d)
              velocity[d] = v[NodalLayout::velocity + d];
            if (node < run.grid.node_partitioner()->locally_owned_size())
              grid_momentum += v[NodalLayout::mass] * velocity;
            if (std::min({x[0], x[1], 1. - x[0], 1. - x[1]}) > 0.375 - 1e-12)
              error =
                std::max(error, (velocity - smooth_field(x)).norm());
          }
        grid_momentum = Utilities::MPI::sum(grid_momentum, MPI_COMM_WORLD);
        momentum_kept = momentum_kept && (grid_momentum - point_momentum).norm() <
                                           1e-13 * point_momentum.norm();
        errors[corrected] = Utilities::MPI::max(error, MPI_COMM_WORLD);
      }
    return errors;
  }

  void
  check_round_trip()
  {
    bool                               momentum_kept = true;
    std::vector<std::array<double, 2>> errors;
    for (const unsigned int n : {8u, 16u, 32u})
      {
        errors.push_back(round_trip_errors(n, momentum_kept));
        deallog << "round trip on " << n << " cells: error lumped "
                << std::setprecision(2) << errors.back()[0] << ", corrected "
                << errors.back()[1] << std::setprecision(6) << std::endl;
      }
    for (unsigned int k = 1; k < errors.size(); ++k)
      {
        const double lumped_rate =
          std::log2(errors[k - 1][0] / errors[k][0]);
        const double corrected_rate =
          std::log2(errors[k - 1][1] / errors[k][1]);
        deallog << "rates " << std::setprecision(3) << lumped_rate << ", "
                << corrected_rate << std::setprecision(6) << std::endl;
        mpm_tests::check("round trip: lumped error falls as h^2",
                         lumped_rate > 1.8 && lumped_rate < 2.2);
        mpm_tests::check("round trip: corrected error falls as h^4",
                         corrected_rate > 3.6);
      }
    mpm_tests::check("both projections keep the momentum to 1e-13",
                     momentum_kept);
  }

  /**
   * A block in the corner of a fixed floor and a slip wall on the left,
   * under gravity and a varying stress: after a nodal solve with the
   * blended mass, the floor's nodes are still at rest and the wall's do
   * not move across it.
   */
  void
  check_blended_mass_walls(const Tensor<1, dim> &gravity)
  {
    ParameterHandler prm;
    mpm_tests::parse_small_scene<dim>(
      prm,
      "subsection Grid\n set Generator = subdivided_hyper_cube\n"
      " set Arguments = 4 : 0 : 1 : true\nend\n"
      "subsection Boundary conditions\n set Fixed boundaries = bottom\n"
      " set Slip boundaries = left\nend\n"
      "subsection body\n set Shape = box\n"
      " set Lower corner = 0, 0\n set Upper corner = 0.5, 0.5\n"
      " set Point placement = Gauss\n set Material = steel\nend\n");
    mpm_tests::SmallExplicitRun<dim> run(prm, gravity);
    run.transfer.enable_blended_mass();
    for (auto &particle : run.points.handler())
      {
        const Point<dim> &    x = particle.get_location();
        SymmetricTensor<2, 3> stress;
        stress[0][0] = 1e3 * std::sin(7. * x[0]) * std::cos(5. * x[1]);
        stress[0][1] = 5e2 * std::cos(3. * x[0] + x[1]);
        Layout::set_stress(particle.get_properties(), stress);
      }
    run.transfer.project_mass_momentum(true);
    run.transfer.compute_nodal_velocity(false);
    run.transfer.compute_nodal_acceleration(1e-4);
    double floor_speed = 0., wall_normal_speed = 0., wall_speed_along = 0.;
    for (const unsigned int node : run.nodes.slots_to_solve())
      {
        const double *    v = run.nodes.values_of(node) + NodalLayout::velocity;
        const Point<dim> &x = run.grid.node_position(node);
        if (x[1] < 1e-12)
          floor_speed = std::max({floor_speed, std::abs(v[0]), std::abs(v[1])});
        else if (x[0] < 1e-12)
          {
            wall_normal_speed = std::max(wall_normal_speed, std::abs(v[0]));
            wall_speed_along  = std::max(wall_speed_along, std::abs(v[1]));
          }
      }
    floor_speed       = Utilities::MPI::max(floor_speed, MPI_COMM_WORLD);
    wall_normal_speed = Utilities::MPI::max(wall_normal_speed, MPI_COMM_WORLD);
    wall_speed_along  = Utilities::MPI::max(wall_speed_along, MPI_COMM_WORLD);
    mpm_tests::check("blended mass: the fixed floor's nodes stay at rest",
                     floor_speed == 0.);
    mpm_tests::check("blended mass: the slip wall's nodes slide along it only",
                     wall_normal_speed == 0. && wall_speed_along > 0.);
  }

  /**
   * A block with a stress that varies from point to point, under gravity:
   * one nodal solve with the blended mass keeps sum m_i a_i = sum m_p g;
   * then the block falls freely with it.
   */
  void
  check_blended_mass_momentum()
  {
    const double   g = 9.81;
    Tensor<1, dim> gravity;
    gravity[dim - 1] = -g;
    ParameterHandler prm;
    mpm_tests::parse_small_scene<dim>(
      prm, mpm_tests::block_in_unit_box<dim>("Gauss"));
    {
      mpm_tests::SmallExplicitRun<dim> run(prm, gravity);
      run.transfer.enable_blended_mass();
      double         mass = 0., stress_scale = 0.;
      for (auto &particle : run.points.handler())
        {
          const ArrayView<double> p = particle.get_properties();
          const Point<dim> &      x = particle.get_location();
          SymmetricTensor<2, 3>   stress;
          stress[0][0] = 1e3 * std::sin(7. * x[0]) * std::cos(5. * x[1]);
          stress[1][1] = 2e3 * x[0] * x[1];
          stress[0][1] = 5e2 * std::cos(3. * x[0] + x[1]);
          Layout::set_stress(p, stress);
          mass += p[Layout::mass];
          stress_scale = std::max(stress_scale, stress.norm());
        }
      mass         = Utilities::MPI::sum(mass, MPI_COMM_WORLD);
      stress_scale = Utilities::MPI::max(stress_scale, MPI_COMM_WORLD);
      run.transfer.project_mass_momentum(true);
      run.transfer.compute_nodal_velocity(false);
      run.transfer.compute_nodal_acceleration(1e-4);
      Tensor<1, dim> grid_force;
      for (const unsigned int node : run.nodes.slots_to_solve())
        if (node < run.grid.node_partitioner()->locally_owned_size())
          for (unsigned int d = 0; d < dim; ++d)
            grid_force[d] += run.nodes.values_of(node)[NodalLayout::mass] *
                             run.nodes.values_of(node)[NodalLayout::force + d];
      grid_force = Utilities::MPI::sum(grid_force, MPI_COMM_WORLD);
      // The internal forces are about stress_scale times the block's edge.
      const double error = (grid_force - mass * gravity).norm();
      mpm_tests::check("blended mass: sum m_i a_i = sum m_p g to 1e-13 of the "
                       "internal forces",
                       error < 1e-13 * stress_scale);
    }
    check_blended_mass_walls(gravity);
    mpm_tests::SmallExplicitRun<dim> run(prm, gravity);
    run.transfer.enable_blended_mass();
    const auto [velocity_error, height_error] =
      mpm_tests::free_fall_errors(run, g, [](unsigned int) {});
    mpm_tests::check("blended mass: free fall exact to 1e-12",
                     velocity_error < 1e-12 && height_error < 1e-12);
  }

  /**
   * An elastic block on a plane with Coulomb friction, gravity tilted by 30
   * degrees (scenes/friction_block.prm: MUSL, pure PIC), with the blended
   * mass: mu = 0.2 slides with the rigid block's g (sin 30 - mu cos 30),
   * mu = 0.7 sticks, the floor's force stays within Coulomb's cone, and it
   * is the force that moves the block.
   */
  void
  check_blended_mass_friction()
  {
    const double g = 9.81, theta = numbers::PI / 6.;
    for (const double mu : {0.2, 0.7})
      {
        const std::string name = "friction-" + std::to_string(mu).substr(0, 3);
        auto              csv  = mpm_tests::run_scene(
          "scenes/friction_block.prm",
          "output-blended-" + name,
          {"Time stepping/Mass matrix=blended",
           "Boundary conditions/Friction boundaries=bottom: " +
             std::to_string(mu)});
        const double x0 = csv["centre_of_mass_x"][0];
        double       num = 0., den = 0., travel = 0., bound = 0.;
        for (unsigned int n = 0; n < csv["time"].size(); ++n)
          {
            const double s  = 0.5 * csv["time"][n] * csv["time"][n],
                         dx = csv["centre_of_mass_x"][n] - x0;
            num += s * dx;
            den += s * s;
            travel = std::max(travel, std::abs(dx));
            bound  = std::max(bound,
                             std::abs(csv["bottom_tangential_force"][n]) -
                               mu * csv["bottom_normal_force"][n]);
          }
        const double weight = 1000. * 0.4 * 0.2 * g;
        mpm_tests::check("blended mass, friction floor: |T| <= mu N",
                         bound < 1e-12 * weight);
        // The floor's law answers the blended change too, so the force it
        // reports is the one that moves the block (Newton's third law).
        mpm_tests::check("blended mass, friction floor: the momentum changes "
                         "by sum dt (M g - F) to 1e-9 of M g t",
                         mpm_tests::floor_momentum_balance(csv, g, theta) <
                           1e-9);
        if (mu < 0.5)
          {
            const double ratio =
              num / den / (g * (std::sin(theta) - mu * std::cos(theta)));
            deallog << "blended mass, mu = 0.2: a / (g (sin - mu cos)) = "
                    << std::setprecision(4) << ratio << std::setprecision(6)
                    << std::endl;
            mpm_tests::check("blended mass, mu = 0.2: the rigid block's "
                             "acceleration within 1 %",
                             std::abs(ratio - 1.) < 0.01);
          }
        else
          mpm_tests::check("blended mass, mu = 0.7: sticks (travel below "
                           "1e-4 m)",
                           travel < 1e-4);
      }
  }

  /**
   * The vibrating bar on `cells` cells with `settings`: its mean period
   * between the first and the last downward zero crossing of the
   * centre-of-mass velocity, and the largest error of that velocity over
   * its amplitude.
   */
  std::pair<double, double>
  bar_run(const unsigned int              cells,
          const std::string &             name,
          const std::vector<std::string> &settings)
  {
    const double L = 25., v0 = 0.1, beta = numbers::PI / (2. * L),
                 omega = beta * std::sqrt(100. / 1.), h = L / cells;
    const double amplitude = v0 / (beta * L);
    std::vector<std::string> all = {
      "Grid/Arguments=" + std::to_string(cells + 2) + ", 1 : 0, 0 : " +
        std::to_string((cells + 2) * h) + ", " + std::to_string(h) +
        " : true",
      "Bodies/bar/Upper corner=25, " + std::to_string(h),
      "Time stepping/Update scheme=USF",
      "Time stepping/CFL number=0.1"};
    all.insert(all.end(), settings.begin(), settings.end());
    auto csv =
      mpm_tests::run_scene("../prm/vibrating_bar.prm", "output-bar-" + name, all);
    std::vector<double> crossings;
    double              error = 0.;
    for (unsigned int n = 0; n < csv["time"].size(); ++n)
      {
        const double v = csv["momentum_x"][n] / csv["mass"][n];
        error          = std::max(error,
                         std::abs(v - amplitude *
                                        std::cos(omega * csv["time"][n])));
        if (n > 0)
          {
            const double before = csv["momentum_x"][n - 1] / csv["mass"][n - 1];
            if (before > 0. && v <= 0.)
              crossings.push_back(csv["time"][n - 1] +
                                  (csv["time"][n] - csv["time"][n - 1]) *
                                    before / (before - v));
          }
      }
    const double period =
      crossings.size() > 1 ?
        (crossings.back() - crossings.front()) / (crossings.size() - 1) :
        0.;
    return {period, error / amplitude};
  }

  void
  check_vibrating_bar()
  {
    const double L = 25., beta = numbers::PI / (2. * L),
                 omega = beta * std::sqrt(100. / 1.), h = L / 16.;
    const double period = 2. * numbers::PI / omega;
    const double x = beta * h / 2., lumped_chain_period = period * x / std::sin(x);
    for (const std::string projection : {"lumped", "corrected", "blended"})
      {
        std::vector<std::string> settings = {
          "Time stepping/Velocity projection=" +
          std::string(projection == "lumped" ? "lumped" : "corrected")};
        if (projection == "blended")
          settings.push_back("Time stepping/Mass matrix=blended");
        const auto [measured, error] = bar_run(16, projection, settings);
        const double chain_error = measured / lumped_chain_period - 1.,
                     exact_error = measured / period - 1.;
        deallog << "bar, 16 cells, " << projection << ": period "
                << std::setprecision(7) << measured << " (lumped chain "
                << lumped_chain_period << ", exact " << period
                << "), error / amplitude " << std::setprecision(2) << error
                << std::setprecision(6) << std::endl;
        if (projection == "corrected")
          {
            mpm_tests::check("bar, corrected: the lumped chain's period "
                             "within 1e-4",
                             std::abs(chain_error) < 1e-4);
            mpm_tests::check("bar, corrected: misses the exact period by "
                             "more than 3e-4",
                             exact_error > 3e-4);
            mpm_tests::check("bar, corrected: within 1 % over 40 s",
                             error < 0.01);
          }
        else if (projection == "blended")
          {
            mpm_tests::check("bar, corrected and blended: the exact period "
                             "within 1e-4",
                             std::abs(exact_error) < 1e-4);
            mpm_tests::check("bar, corrected and blended: within 1 % over "
                             "40 s",
                             error < 0.01);
          }
        else
          mpm_tests::check("bar, lumped: the period misses the chain's by "
                           "more than 5e-4",
                           chain_error > 5e-4);
      }
    for (const unsigned int cells : {16u, 32u, 64u})
      {
        const double error =
          bar_run(cells,
                  "uGIMP-" + std::to_string(cells),
                  {"Grid/Shape functions=uGIMP",
                   "Time stepping/Velocity projection=corrected",
                   "Time stepping/Mass matrix=blended"})
            .second;
        deallog << "bar, " << cells
                << " cells, uGIMP, corrected and blended: error / amplitude "
                << std::setprecision(2) << error << std::setprecision(6)
                << std::endl;
        mpm_tests::check("bar, uGIMP, corrected and blended: within 1 % over "
                         "40 s",
                         error < 0.01);
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  check_round_trip();
  check_blended_mass_momentum();
  check_blended_mass_friction();
  check_vibrating_bar();
}
