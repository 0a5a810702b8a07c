#include <mpm/assembly/point_assembly.h>
#include <mpm/base/input_error.h>
#include <mpm/points/point_state.h>
#include <mpm/time/cloud_system.h>
#include <mpm/time/grid_system.h>
#include <mpm/time/implicit_integrator.h>

#include <algorithm>
#include <string>

namespace mpm
{
  template <int dim>
  void
  ImplicitIntegrator<dim>::declare_parameters(ParameterHandler &prm)
  {
    NewtonSolver<dim>::declare_parameters(prm);
    GridSystem<dim>::declare_parameters(prm);
    Newmark::declare_parameters(prm);
  }



  namespace
  {
    /** The system of the method: the grid's, or the node cloud's. */
    template <int dim>
    std::unique_ptr<ImplicitSystem<dim>>
    make_system(ParameterHandler &                  prm,
                MaterialPoints<dim> &               points,
                const Grid<dim> &                   grid,
                const GridBasis<dim> &              basis,
                const std::vector<const NodalCondition<dim> *> &conditions,
                const DirichletConditions<dim> &    dirichlet,
                std::unique_ptr<MeshfreeBasis<dim>> meshfree,
                const Newmark &                     newmark,
                ConditionalOStream &                pcout,
                TimerOutput &                       timer)
    {
      if (meshfree)
        return std::make_unique<CloudSystem<dim>>(
          points, grid, dirichlet, std::move(meshfree), newmark, pcout, timer);
      return std::make_unique<GridSystem<dim>>(
        prm, points, grid, basis, conditions, pcout);
    }
  } // namespace



  template <int dim>
  ImplicitIntegrator<dim>::ImplicitIntegrator(
    const bool                                    dynamic,
    ParameterHandler &                            prm,
    MaterialPoints<dim> &                         points,
    const Grid<dim> &                             grid,
    const GridBasis<dim> &                        basis,
    const std::vector<const NodalCondition<dim> *> &conditions,
    const DirichletConditions<dim> &              dirichlet,
    const std::vector<std::unique_ptr<Material>> &materials,
    const Tensor<1, dim> &                        gravity,
    ConditionalOStream &                          pcout,
    TimerOutput &                                 timer,
    std::unique_ptr<MeshfreeBasis<dim>>           meshfree)
    : points(points)
    , materials(materials)
    , timer(timer)
    , newmark(prm, dynamic)
    , system(make_system(prm,
                         points,
                         grid,
                         basis,
                         conditions,
                         dirichlet,
                         std::move(meshfree),
                         newmark,
                         pcout,
                         timer))
    , newton(prm, grid, pcout, timer)
    , assembler(points, materials, gravity, newmark)
  {
    state.dynamic                      = dynamic;
    state.keeps_unconstrained_residual =
      std::any_of(conditions.begin(),
                  conditions.end(),
                  [](const NodalCondition<dim> *condition) {
                    return condition->has_unilateral_nodes();
                  });
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::step(const double load_factor, const double dt)
  {
    // A failed step is retried with half the size from the same state, so
    // the walls' active set must not keep what the failed attempt did.
    system->remember_active_set();
    try
      {
        solve_step(load_factor, dt);
      }
    catch (...)
      {
        system->restore_active_set();
        throw;
      }
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::solve_step(const double load_factor,
                                      const double dt)
  {
    state.time_step = dt;
    {
      TimerOutput::Scope t(timer, "setup system");
      system->setup(state);
      if (state.dynamic)
        system->project_initial_conditions(state);
    }
    // Dynamic runs start Newton a tenth of the way along the
    // constant-velocity predictor, du = dt v_n / 10. The full predictor
    // dt v_n puts each point at a trial state one step of extrapolated
    // motion away, where plastic flow has points that land, leave the
    // apex or change plane: the first tangent is taken there. Near the
    // last converged state it is the tangent of the flow as it was, and
    // the first correction fixes the inertia force that the short start
    // leaves (of order m v_n / dt). On the cohesive column (h = 0.025, to
    // 0.3 s) the full predictor costs 563 Newton iterations and 4 cut
    // steps, a tenth of it 405 and 1, no start at all (du = 0) 439 and 2;
    // du = 0 would also put every point that ended the last step on its
    // yield surface at a kink of the residual. The acceleration term
    // dt^2/2 a_n is left out: the projected accelerations are the
    // noisiest field in plastic flow, and it cost 35 % more iterations
    // (doc/benchmarks.md).
    state.displacement = 0.;
    if (state.dynamic)
      {
        constexpr double predictor_fraction = 0.1;
        state.displacement.add(predictor_fraction * dt,
                               state.projected_velocity);
        state.constraints.distribute(state.displacement);
      }
    state.displacement_ghosted = state.displacement;

    // Walls with an active set: solve, correct the set (and with it the
    // constraints), and solve again from there until the set holds. A node
    // changes at most once per step: a node that pulls while held but moves
    // into the wall when free would otherwise flip for ever.
    constexpr unsigned int max_contact_rounds = 10;
    for (unsigned int round = 1;; ++round)
      {
        newton.solve(state, assembler, load_factor);
        if (!system->has_active_set() || !system->update_active_set(state))
          break;
        if (round == max_contact_rounds)
          throw RunError("The contact nodes did not settle in " +
                         std::to_string(max_contact_rounds) +
                         " rounds of the step.");
        state.constraints.distribute(state.displacement);
        state.displacement_ghosted = state.displacement;
        if (state.dynamic)
          state.constrain_initial_conditions();
      }
    TimerOutput::Scope t(timer, "G2P");
    update_points();
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::update_points()
  {
    using Layout                    = PointLayout<dim>;
    const unsigned int acceleration = points.slot_index("acceleration");
    std::vector<Tensor<1, dim>> du, v_n, a_n;
    for (const auto &group : state.groups)
      {
        state.gather(group, du, v_n, a_n);
        for (unsigned int q = 0; q < group.particles.size(); ++q)
          {
            const Support<dim> &support  = group.supports[q];
            auto                particle = group.particles[q];
            const ArrayView<double> p = particle->get_properties();
            const Tensor<2, dim>    dF =
              PointAssembly<dim>::deformation_increment(support, du);
            const StepKinematics k = ImplicitAssembler<dim>::step_kinematics(
              dF,
              ImplicitAssembler<dim>::hoop_increment(
                points.get_grid().geometry(),
                support,
                du,
                particle->get_location()),
              p,
              state.time_step);
            // The assembly at this iterate met sigma_zz = 0 at every
            // point, so in plane stress the same solve succeeds here.
            AssertThrow(PointState<dim>::commit(
                          materials,
                          k,
                          p,
                          points.get_grid().geometry().free_faces()),
                        ExcInternalError());

            Tensor<1, dim> displacement_at_point;
            for (unsigned int i = 0; i < support.n_nodes; ++i)
              displacement_at_point += support.N[i] * du[i];
            if (state.dynamic)
              {
                // [I] eqs. 46-49: the points take the nodal acceleration at
                // the end of the step, and the Newmark velocity update.
                Tensor<1, dim> a_old, a_new;
                for (unsigned int i = 0; i < support.n_nodes; ++i)
                  {
                    a_old += support.N[i] * a_n[i];
                    a_new +=
                      support.N[i] *
                      newmark.end_acceleration(
                        du[i], v_n[i], a_n[i], state.time_step);
                  }
                const Tensor<1, dim> dv =
                  newmark.velocity_increment(a_old, a_new, state.time_step);
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    p[Layout::velocity + d] += dv[d];
                    p[acceleration + d] = a_new[d];
                  }
              }
            particle->set_location(particle->get_location() +
                                   displacement_at_point);
          }
      }
    system->finish_step(state);
  }



  template class ImplicitIntegrator<2>;
  template class ImplicitIntegrator<3>;
} // namespace mpm
