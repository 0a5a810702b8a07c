// Velocity fields at the nodes (GridNodes with K fields), on one and two
// ranks: the two elastic disks of prm/two_disks.prm (Sulsky et al.), moving
// towards each other at 0.1 sqrt(2) m/s, run by ExplicitIntegrator (MUSL,
// dt = 0.01 s) for 4.5 s. Free, they would overlap from t = 1.59 s to
// 4.41 s and have swapped places at 4.5 s (centres at 0.65 and 0.35).
// - One field for both disks, to 3.5 s (as the scene; later the disks
//   leave the grid): the grid makes them one velocity field where
//   they meet, so they collide and bounce back: the lower disk's momentum
//   reverses (to below -1/2 of its start in both components), and the
//   total stays zero (1e-12 of m v0).
// - A field per disk and nothing coupling them: each disk moves as if the
//   other were not there. A uniform velocity field has no strain rate, so
//   each disk translates rigidly: its momentum stays m v0 (1e-12) and its
//   centre moves by v0 t (1e-10 m), through the other disk and past it.
//   The fields share nodes at least while the disks overlap (282 steps)
//   and at most while their gap is below two cell diagonals (382 steps).
//   The grid output's nodal mass sums to both disks' mass (1e-12), and its
//   velocity is the centre-of-mass velocity: at t = 3 s the centres meet
//   at the node (0.5, 0.5), which the two disks' points, mirror images
//   through it, fill alike, so its velocity is zero (1e-12 m/s).
// On two ranks the disks cross the ranks' border, so the fields' values at
// ghost nodes go to their owners and back.

#include <deal.II/base/mpi.h>

#include <mpm/core/application.h>

#include <cmath>

#include "small_scene.h"

using namespace dealii;

namespace
{
  constexpr unsigned int dim = 2;
  using Layout               = mpm::PointLayout<dim>;
  using NodalLayout          = mpm::GridNodes<dim>::NodalLayout;

  const char *scene = R"(
subsection Grid
  set Arguments = 20, 20 : 0, 0 : 1, 1 : true
end
subsection body
  set Shape    = disk
  set Center   = 0.2, 0.2
  set Radius   = 0.2
  set Material = steel
  set Initial velocity = 0.1; 0.1
end
subsection upper
  set Shape    = disk
  set Center   = 0.8, 0.8
  set Radius   = 0.2
  set Material = steel
  set Initial velocity = -0.1; -0.1
end
subsection material
  set Density         = 1000
  set Young's modulus = 1000
  set Poisson's ratio = 0.3
end
)";

  /** Per body (by id): mass, momentum, mass times centre. */
  struct BodySums
  {
    double         mass[2] = {};
    Tensor<1, dim> momentum[2];
    Tensor<1, dim> moment[2];

    Point<dim>
    centre(const unsigned int b) const
    {
      return Point<dim>(moment[b] / mass[b]);
    }
  };

  BodySums
  body_sums(const mpm::MaterialPoints<dim> &points)
  {
    BodySums sums;
    for (const auto &particle : points.handler())
      {
        const ArrayView<const double> p = particle.get_properties();
        const unsigned int b = static_cast<unsigned int>(p[Layout::body_id]);
        sums.mass[b] += p[Layout::mass];
        sums.momentum[b] += p[Layout::mass] * Layout::get_velocity(p);
        sums.moment[b] += p[Layout::mass] * particle.get_location();
      }
    const MPI_Comm comm = MPI_COMM_WORLD;
    for (unsigned int b = 0; b < 2; ++b)
      {
        sums.mass[b]     = Utilities::MPI::sum(sums.mass[b], comm);
        sums.momentum[b] = Utilities::MPI::sum(sums.momentum[b], comm);
        sums.moment[b]   = Utilities::MPI::sum(sums.moment[b], comm);
      }
    return sums;
  }

  /** The two disks, in one field or in one each. */
  void
  run_disks(const bool field_per_body)
  {
    ParameterHandler prm;
    mpm::Grid<dim>::declare_parameters(prm);
    mpm::DirichletConditions<dim>::declare_parameters(prm);
    for (const char *body : {"body", "upper"})
      {
        prm.enter_subsection(body);
        mpm::Body<dim>::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.enter_subsection("material");
    mpm::Material::declare_parameters(prm);
    prm.leave_subsection();
    prm.parse_input_from_string(scene);

    mpm::Grid<dim> grid(prm, MPI_COMM_WORLD);
    grid.create();
    mpm::GridNodes<dim> nodes(grid, field_per_body ? 2 : 1);
    nodes.setup();
    mpm::GridBasis<dim>                          basis(grid);
    mpm::MaterialPoints<dim>                     points(grid, {});
    std::vector<std::unique_ptr<mpm::Material>> materials;
    prm.enter_subsection("material");
    materials.push_back(mpm::Material::create(prm, "steel", "material"));
    prm.leave_subsection();
    std::vector<mpm::Body<dim>> bodies;
    for (const char *body : {"body", "upper"})
      {
        prm.enter_subsection(body);
        bodies.emplace_back(prm, body, body, std::vector<std::string>{"steel"});
        prm.leave_subsection();
      }
    mpm::PointSeeder<dim> seeder(grid);
    seeder.release_due(bodies, materials, points, 0., 0.);

    const std::vector<unsigned int> field_of_body =
      field_per_body ? std::vector<unsigned int>{0, 1} :
                       std::vector<unsigned int>{};
    mpm::GridTransfer<dim> transfer(
      points, basis, nodes, {}, Tensor<1, dim>(), field_of_body);
    TimerOutput timer(MPI_COMM_WORLD,
                      deallog.get_console(),
                      TimerOutput::never,
                      TimerOutput::wall_times);
    mpm::ExplicitIntegrator<dim> integrator(
      transfer,
      materials,
      mpm::ExplicitIntegrator<dim>::Scheme::MUSL,
      0.,
      false,
      grid,
      timer);

    const BodySums     start   = body_sums(points);
    const double       dt      = 0.01;
    const unsigned int n_steps = field_per_body ? 450 : 350;
    unsigned int       steps_shared = 0;
    double             output_mass_error = 0.;
    double             centre_velocity_error = 0.;
    for (unsigned int n = 1; n <= n_steps; ++n)
      {
        integrator.step(dt);
        points.sort();
        if (!field_per_body)
          continue;
        const std::vector<unsigned int> shared = nodes.shared_nodes();
        if (Utilities::MPI::logical_or(!shared.empty(), MPI_COMM_WORLD))
          ++steps_shared;
        // The grid output: the fields' mass summed, their centre-of-mass
        // velocity, over the owned nodes.
        const auto &out = nodes.output_vector();
        double      mass = 0.;
        for (unsigned int node = 0;
             node < grid.node_partitioner()->locally_owned_size();
             ++node)
          mass += out.local_element(node * NodalLayout::n_components +
                                    NodalLayout::mass);
        mass = Utilities::MPI::sum(mass, MPI_COMM_WORLD);
        output_mass_error = std::max(
          output_mass_error,
          std::abs(mass - start.mass[0] - start.mass[1]) / mass);
        if (n == 300)
          for (const unsigned int node : shared)
            {
              const Point<dim> &x = grid.node_position(node);
              if (std::abs(x[0] - 0.5) < 1e-9 && std::abs(x[1] - 0.5) < 1e-9)
                for (unsigned int d = 0; d < dim; ++d)
                  centre_velocity_error = std::max(
                    centre_velocity_error,
                    std::abs(out.local_element(
                      node * NodalLayout::n_components +
                      NodalLayout::velocity + d)));
            }
      }
    const BodySums end   = body_sums(points);
    const double   t     = n_steps * dt;
    const double   m_v0  = start.momentum[0].norm();
    const double   total = (end.momentum[0] + end.momentum[1]).norm();
    deallog << (field_per_body ? "a field per disk" : "one field")
            << std::endl;
    mpm_tests::check("the total momentum stays zero (1e-12 of m v0)",
                     total < 1e-12 * m_v0);
    if (!field_per_body)
      {
        // The lower disk (body 0) moved up and right; after the collision
        // it moves back.
        mpm_tests::check("the disks collide: the lower disk's momentum "
                         "reverses",
                         end.momentum[0][0] < -0.5 * start.momentum[0][0] &&
                           end.momentum[0][1] < -0.5 * start.momentum[0][1]);
        return;
      }
    double momentum_error = 0., centre_error = 0.;
    for (unsigned int b = 0; b < 2; ++b)
      {
        momentum_error = std::max(momentum_error,
                                  (end.momentum[b] - start.momentum[b]).norm() /
                                    m_v0);
        const Tensor<1, dim> v0 = start.momentum[b] / start.mass[b];
        centre_error = std::max(
          centre_error, (end.centre(b) - start.centre(b) - t * v0).norm());
      }
    mpm_tests::check("each disk keeps its momentum (1e-12 of m v0)",
                     momentum_error < 1e-12);
    mpm_tests::check("each centre moves by v0 t (1e-10 m)",
                     centre_error < 1e-10);
    mpm_tests::check("the disks pass through each other",
                     end.centre(0)[0] > end.centre(1)[0] &&
                       end.centre(0)[1] > end.centre(1)[1]);
    mpm_tests::check("the fields share nodes in 282 to 382 of the 450 steps",
                     steps_shared >= 282 && steps_shared <= 382);
    mpm_tests::check("the grid output's mass is both disks' (1e-12)",
                     output_mass_error < 1e-12);
    mpm_tests::check("its velocity where both disks fill a node alike is "
                     "their centre of mass's, zero (1e-12 m/s)",
                     Utilities::MPI::max(centre_velocity_error,
                                         MPI_COMM_WORLD) < 1e-12);
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  mpm_tests::initlog();
  run_disks(false);
  run_disks(true);
}
