// The contract of a nodal condition in the explicit nodal solve
// (NodalCondition::constrain_explicit() and constrain_change()), tested on
// the conditions alone: a unit square of 2 x 2 cells, a slip wall on the
// left, a fixed floor and a Coulomb wall (mu = 1/2) on top, and no points.
// The solve is handed a node's mass m = 2, velocity v and acceleration a
// (dt = 0.1); after it, the node ends the step with v + dt a.
// - Slip (the node (0, 1/2)): the end velocity has no normal component,
//   exactly, and keeps its tangential one; the velocity alone
//   (constrain_velocity()) likewise.
// - Fixed (the node (1/2, 0)): the end velocity is zero.
// - Neither acts on the middle node.
// - Coulomb wall (the node (1/2, 1), outward normal +y), against the closed
//   form of the m/dt penalty limit: moving in with v_n = 1/2 and a slide
//   v_t = 1/10 below mu v_n, the node sticks (end velocity 0) and the wall
//   reports a normal force m v_n / dt = 10 and a tangential one
//   m v_t / dt = 2; with v_t = 1 it slips to (1 - mu v_n / v_t) v_t = 3/4
//   and the tangential force is mu times the normal one, 5; moving away it
//   is left alone and reports nothing; a blended-mass change that keeps a
//   sticking node in the cone is taken whole by the wall.
// - Two velocity fields at one node (two slots) are solved one by one and
//   their reactions add: two fields of mass 1 each report the force of one
//   of mass 2.
// All to 1e-12.

#include <deal.II/base/mpi.h>

#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/boundary/friction_walls.h>
#include <mpm/core/application.h>
#include <mpm/grid/grid.h>

#include <cmath>

#include "tests.h"

using namespace dealii;

namespace
{
  constexpr unsigned int dim = 2;
  constexpr double       dt  = 0.1;
  constexpr double       m   = 2.;

  unsigned int
  node_at(const mpm::Grid<dim> &grid, const Point<dim> &x)
  {
    for (unsigned int node = 0; node < grid.n_nodes(); ++node)
      if (grid.node_position(node).distance(x) < 1e-12)
        return node;
    AssertThrow(false, ExcMessage("no node there"));
    return 0;
  }

  /**
   * One explicit solve of a condition at a node: the end velocity v + dt a
   * it leaves.
   */
  Tensor<1, dim>
  end_velocity(const mpm::NodalCondition<dim> &condition,
               const unsigned int              node,
               const unsigned int              slot,
               const double                    mass,
               const Tensor<1, dim> &          v,
               const Tensor<1, dim> &          a)
  {
    double velocity[dim], acceleration[dim];
    for (unsigned int d = 0; d < dim; ++d)
      {
        velocity[d]     = v[d];
        acceleration[d] = a[d];
      }
    condition.constrain_explicit(node, slot, mass, velocity, acceleration, dt, 0.);
    Tensor<1, dim> end;
    for (unsigned int d = 0; d < dim; ++d)
      end[d] = velocity[d] + dt * acceleration[d];
    return end;
  }

  bool
  close(const double a, const double b)
  {
    return std::abs(a - b) < 1e-12;
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();

  ParameterHandler prm;
  mpm::Grid<dim>::declare_parameters(prm);
  mpm::DirichletConditions<dim>::declare_parameters(prm);
  mpm::FrictionWalls<dim>::declare_parameters(prm);
  prm.parse_input_from_string(R"(
subsection Grid
  set Arguments = 2, 2 : 0, 0 : 1, 1 : true
end
subsection Boundary conditions
  set Slip boundaries     = left
  set Fixed boundaries    = bottom
  set Friction boundaries = top: 0.5
end
)");
  mpm::Grid<dim> grid(prm, MPI_COMM_WORLD);
  grid.create();
  mpm::DirichletConditions<dim> dirichlet(prm, grid);
  mpm::FrictionWalls<dim>       walls(prm, grid);
  dirichlet.setup();
  walls.setup();

  const unsigned int slip   = node_at(grid, Point<dim>(0., 0.5));
  const unsigned int fixed  = node_at(grid, Point<dim>(0.5, 0.));
  const unsigned int top    = node_at(grid, Point<dim>(0.5, 1.));
  const unsigned int middle = node_at(grid, Point<dim>(0.5, 0.5));

  // Dirichlet walls.
  {
    const Tensor<1, dim> v({0.3, 0.2}), a({1., -2.});
    const Tensor<1, dim> end = end_velocity(dirichlet, slip, slip, m, v, a);
    mpm_tests::check("slip: no normal end velocity, the tangential kept",
                     end[0] == 0. && close(end[1], v[1] + dt * a[1]));
    double velocity[dim] = {0.3, 0.2};
    dirichlet.constrain_velocity(slip, velocity);
    mpm_tests::check("slip: constrain_velocity() likewise",
                     velocity[0] == 0. && velocity[1] == 0.2);
    const Tensor<1, dim> held = end_velocity(dirichlet, fixed, fixed, m, v, a);
    mpm_tests::check("fixed: no end velocity", held.norm() == 0.);
    mpm_tests::check("neither acts on the middle node",
                     !dirichlet.acts_on(middle) && !walls.acts_on(middle) &&
                       dirichlet.acts_on(slip) && walls.acts_on(top));
  }

  // The Coulomb wall; forces() gives top_normal_force and
  // top_tangential_force.
  const auto wall_forces = [&](const double mass, const Tensor<1, dim> &v) {
    walls.begin_explicit_solve(0., dt);
    const Tensor<1, dim> end =
      end_velocity(walls, top, top, mass, v, Tensor<1, dim>());
    const std::vector<double> f = walls.forces();
    return std::make_tuple(end, f[0], std::abs(f[1]));
  };
  {
    const auto [end, normal, tangential] =
      wall_forces(m, Tensor<1, dim>({0.1, 0.5}));
    mpm_tests::check("Coulomb stick: no end velocity, N = m v_n / dt, "
                     "T = m v_t / dt",
                     end.norm() == 0. && close(normal, 10.) &&
                       close(tangential, 2.));
    double change[dim] = {0.2, 0.};
    walls.constrain_change(top, top, change);
    mpm_tests::check("a change that keeps it in the cone is the wall's",
                     close(change[0], 0.) && close(change[1], 0.));
  }
  {
    const auto [end, normal, tangential] =
      wall_forces(m, Tensor<1, dim>({1., 0.5}));
    mpm_tests::check("Coulomb slip: end (1 - mu v_n / v_t) v_t, T = mu N",
                     close(end[0], 0.75) && close(end[1], 0.) &&
                       close(normal, 10.) && close(tangential, 5.));
  }
  {
    const Tensor<1, dim> away({0.3, -0.2});
    const auto [end, normal, tangential] = wall_forces(m, away);
    mpm_tests::check("moving away: left alone, no force",
                     end == away && normal == 0. && tangential == 0.);
  }
  {
    // Two fields of mass 1 at the node: the slot of field 0 is the node,
    // another field's any other number.
    walls.begin_explicit_solve(0., dt);
    const Tensor<1, dim> v({0.1, 0.5});
    const Tensor<1, dim> end0 = end_velocity(walls, top, top, 1., v, {});
    const Tensor<1, dim> end1 =
      end_velocity(walls, top, grid.n_nodes(), 1., v, {});
    const std::vector<double> f = walls.forces();
    mpm_tests::check("two fields: each solved alone, the forces add",
                     end0.norm() == 0. && end1.norm() == 0. &&
                       close(f[0], 10.) && close(std::abs(f[1]), 2.));
  }
}
