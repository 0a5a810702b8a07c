#include <mpm/time/implicit_system.h>

namespace mpm
{
  template <int dim>
  void
  ImplicitSystem<dim>::project_initial_conditions(ImplicitState<dim> &state)
  {
    using Layout        = PointLayout<dim>;
    const unsigned int acceleration = points.slot_index("acceleration");
    const MPI_Comm comm = points.get_communicator();
    state.projected_velocity.reinit(state.owned_dofs, comm);
    state.projected_acceleration.reinit(state.owned_dofs, comm);
    // Writable ghost entries, summed into their owners by compress().
    TrilinosWrappers::MPI::Vector mass, momentum, mass_acceleration;
    mass.reinit(state.owned_dofs, state.relevant_dofs, comm, true);
    momentum.reinit(state.owned_dofs, state.relevant_dofs, comm, true);
    mass_acceleration.reinit(state.owned_dofs, state.relevant_dofs, comm, true);

    for (const auto &group : state.groups)
      for (unsigned int q = 0; q < group.particles.size(); ++q)
        {
          const Support<dim> &          support = group.supports[q];
          const ArrayView<const double> p =
            group.particles[q]->get_properties();
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            for (unsigned int a = 0; a < dim; ++a)
              {
                const types::global_dof_index dof = group.dofs[i * dim + a];
                const double Nm = support.N[i] * p[Layout::mass];
                mass(dof) += Nm;
                momentum(dof) += Nm * p[Layout::velocity + a];
                mass_acceleration(dof) +=
                  Nm * p[acceleration + a];
              }
        }
    mass.compress(VectorOperation::add);
    momentum.compress(VectorOperation::add);
    mass_acceleration.compress(VectorOperation::add);

    for (const auto i : state.owned_dofs)
      if (mass(i) > 0.)
        {
          state.projected_velocity(i)     = momentum(i) / mass(i);
          state.projected_acceleration(i) = mass_acceleration(i) / mass(i);
        }
    state.projected_velocity.compress(VectorOperation::insert);
    state.projected_acceleration.compress(VectorOperation::insert);
    state.constrain_initial_conditions();
  }



  template class ImplicitSystem<2>;
  template class ImplicitSystem<3>;
} // namespace mpm
