#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/sparsity_tools.h>

#include <mpm/base/input_error.h>
#include <mpm/time/grid_system.h>

#include <cmath>

namespace mpm
{
  template <int dim>
  void
  GridSystem<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newton");
    prm.declare_entry(
      "Integration", "full cells by cell volume",
      Patterns::Selection("material points|full cells by cell volume"),
      "Quadrature of the internal force. 'material points': each point "
      "weighs its own volume. 'full cells by cell volume': in cells whose "
      "face neighbours all hold material, the point volumes are scaled to "
      "fill the cell, so a uniform stress is in equilibrium however points "
      "have crossed cells (after Beuth et al., who use Gauss points in full "
      "cells); cells on the material's surface keep point volumes. MPM "
      "only: the meshfree methods always weigh point volumes, as Iaconeta "
      "et al. do.");
    prm.leave_subsection();
  }



  template <int dim>
  GridSystem<dim>::GridSystem(ParameterHandler &              prm,
                              MaterialPoints<dim> &           points,
                              const Grid<dim> &               grid,
                              const GridBasis<dim> &          basis,
                              const std::vector<const NodalCondition<dim> *>
                                &conditions,
                              ConditionalOStream &            pcout)
    : ImplicitSystem<dim>(points)
    , grid(grid)
    , basis(basis)
    , conditions(conditions)
    , pcout(pcout)
    , dof_handler(points.get_triangulation())
  {
    prm.enter_subsection("Newton");
    scale_full_cells = prm.get("Integration") == "full cells by cell volume";
    prm.leave_subsection();
    fe_collection.push_back(FESystem<dim>(FE_Q<dim>(1), dim));
    fe_collection.push_back(FESystem<dim>(FE_Nothing<dim>(), dim));
    grid_changed =
      grid.changed.connect([this]() { contact = ContactActiveSet(); });
  }



  template <int dim>
  void
  GridSystem<dim>::setup(ImplicitState<dim> &state)
  {
    contact.begin_step();
    // Unknowns only on cells that hold points.
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        cell->set_active_fe_index(
          this->points.handler().n_particles_in_cell(cell) > 0 ? 0 : 1);
    dof_handler.distribute_dofs(fe_collection);
    state.owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, state.relevant_dofs);

    // Contact nodes stay engaged into the new step only while material
    // still touches them.
    if (has_active_set())
      {
        const TrilinosWrappers::MPI::Vector touching =
          contact_gaps(state, false);
        for_each_contact_node(
          [&](const unsigned int node, const types::global_dof_index dof0,
              const auto &) {
            if (touching(dof0) == 0.)
              contact.let_go(node, 0);
          });
      }
    make_constraints(state);

    const MPI_Comm         comm = this->points.get_communicator();
    DynamicSparsityPattern dsp(state.relevant_dofs);
    // Constrained rows keep their entries, so that releasing a contact node
    // needs no new pattern.
    DoFTools::make_sparsity_pattern(dof_handler, dsp, state.constraints, true);
    SparsityTools::distribute_sparsity_pattern(dsp, state.owned_dofs, comm,
                                               state.relevant_dofs);
    state.reinit(dsp, comm);
    build_cell_groups(state);
  }



  template <int dim>
  void
  GridSystem<dim>::build_cell_groups(ImplicitState<dim> &state) const
  {
    unsigned int n_groups = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned() || cell->active_fe_index() != 0)
          continue;
        auto &group = state.next_group(n_groups);
        group.dofs.resize(fe_collection[0].n_dofs_per_cell());
        cell->get_dof_indices(group.dofs);
        group.weight = quadrature_scale(cell);
        group.supports.resize(this->points.handler().n_particles_in_cell(cell));
        unsigned int q = 0;
        const auto cell_points = this->points.handler().particles_in_cell(cell);
        for (auto particle = cell_points.begin(); particle != cell_points.end();
             ++particle, ++q)
          {
            group.particles.push_back(particle);
            basis.evaluate(cell->active_cell_index(),
                           particle->get_reference_location(),
                           group.supports[q]);
          }
      }
    state.groups.resize(n_groups);
  }



  template <int dim>
  double
  GridSystem<dim>::quadrature_scale(
    const typename DoFHandler<dim>::active_cell_iterator &cell) const
  {
    if (!scale_full_cells)
      return 1.;
    // Neighbours (owned or ghost) that hold points carry FE_Q.
    for (const unsigned int f : cell->face_indices())
      if (!cell->at_boundary(f) && cell->neighbor(f)->active_fe_index() != 0)
        return 1.;
    using Layout  = PointLayout<dim>;
    double volume = 0.;
    for (const auto &particle : this->points.handler().particles_in_cell(cell))
      {
        const ArrayView<const double> p = particle.get_properties();
        volume += Layout::current_volume(p);
      }
    return cell->measure() / volume;
  }



  template <int dim>
  void
  GridSystem<dim>::make_constraints(ImplicitState<dim> &state) const
  {
    // Grid conditions on the nodes of active cells: a wall along an axis
    // fixes that component; a slanted wall ties the components so that the
    // normal displacement vanishes.
    state.constraints.clear();
    state.constraints.reinit(state.relevant_dofs);
    bool unsupported_corner = false;
    DoFTools::make_hanging_node_constraints(dof_handler, state.constraints);
    for_each_constrained_vertex([&](const auto &                cell,
                                    const unsigned int          v,
                                    const unsigned int          node,
                                    const NodalCondition<dim> &condition) {
      std::array<types::global_dof_index, dim> dofs;
      for (unsigned int a = 0; a < dim; ++a)
        dofs[a] = cell->vertex_dof_index(v, a, 0);
      if (!condition.add_constraints(
            node, dofs, contact.holds(node, 0), state.constraints))
        unsupported_corner = true;
    });
    // Decided on all ranks together, so that all stop.
    if (Utilities::MPI::logical_or(unsupported_corner,
                                   this->points.get_communicator()))
      throw RunError("Boundary conditions: the implicit schemes support "
                     "corners between slip walls only when the walls are "
                     "aligned with the axes, and material reached such a "
                     "corner.");
    state.constraints.close();
  }



  template <int dim>
  template <typename Function>
  void
  GridSystem<dim>::for_each_constrained_vertex(const Function &f) const
  {
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned() || cell->active_fe_index() != 0)
          continue;
        for (const unsigned int v : cell->vertex_indices())
          {
            const unsigned int node =
              grid.node_of(cell->active_cell_index(), v);
            for (const NodalCondition<dim> *condition : conditions)
              if (condition->acts_on(node))
                f(cell, v, node, *condition);
          }
      }
  }



  template <int dim>
  template <typename Function>
  void
  GridSystem<dim>::for_each_contact_node(const Function &f) const
  {
    std::set<unsigned int> visited;
    for_each_constrained_vertex([&](const auto &                cell,
                                    const unsigned int          v,
                                    const unsigned int          node,
                                    const NodalCondition<dim> &condition) {
      const Tensor<1, dim> *outward = condition.unilateral_normal(node);
      if (outward != nullptr && visited.insert(node).second)
        f(node, cell->vertex_dof_index(v, 0, 0), *outward);
    });
  }



  template <int dim>
  TrilinosWrappers::MPI::Vector
  GridSystem<dim>::contact_gaps(const ImplicitState<dim> &state,
                               const bool                after_solve) const
  {
    using Layout         = PointLayout<dim>;
    const MPI_Comm comm  = this->points.get_communicator();
    // Summed over the ranks that share a node, so that all decide alike.
    TrilinosWrappers::MPI::Vector flags;
    flags.reinit(state.owned_dofs, state.relevant_dofs, comm, true);
    std::vector<types::global_dof_index> dofs(
      fe_collection[0].n_dofs_per_cell());
    Support<dim> support;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned() || cell->active_fe_index() != 0)
          continue;
        // (vertex, outward normal of its unilateral wall)
        std::vector<std::pair<unsigned int, const Tensor<1, dim> *>>
          contact_vertices;
        for (const unsigned int v : cell->vertex_indices())
          {
            const unsigned int node =
              grid.node_of(cell->active_cell_index(), v);
            for (const NodalCondition<dim> *condition : conditions)
              if (condition->acts_on(node))
                if (const Tensor<1, dim> *outward =
                      condition->unilateral_normal(node))
                  contact_vertices.emplace_back(v, outward);
          }
        if (contact_vertices.empty())
          continue;
        cell->get_dof_indices(dofs);
        for (const auto &particle :
             this->points.handler().particles_in_cell(cell))
          {
            const ArrayView<const double> p = particle.get_properties();
            const double reach = this->reach_of(p);
            Point<dim> x = particle.get_location();
            if (after_solve)
              {
                basis.evaluate(cell->active_cell_index(),
                               particle.get_reference_location(),
                               support);
                for (unsigned int i = 0; i < support.n_nodes; ++i)
                  for (unsigned int a = 0; a < dim; ++a)
                    x[a] += support.N[i] *
                            state.displacement_ghosted(dofs[i * dim + a]);
              }
            for (const auto &[v, outward] : contact_vertices)
              {
                const double gap_before =
                  (cell->vertex(v) - particle.get_location()) * *outward;
                const double gap = (cell->vertex(v) - x) * *outward;
                if (gap < reach && (!after_solve || gap < gap_before))
                  flags(cell->vertex_dof_index(v, 0, 0)) += 1.;
              }
          }
      }
    flags.compress(VectorOperation::add);
    TrilinosWrappers::MPI::Vector ghosted(state.owned_dofs,
                                          state.relevant_dofs,
                                          comm);
    ghosted = flags;
    return ghosted;
  }



  template <int dim>
  bool
  GridSystem<dim>::update_active_set(ImplicitState<dim> &state)
  {
    const MPI_Comm                      comm = this->points.get_communicator();
    const TrilinosWrappers::MPI::Vector residual_at_nodes =
      state.wall_reactions(comm);
    unsigned int released = 0, engaged = 0;
    const TrilinosWrappers::MPI::Vector closing = contact_gaps(state, true);
    // Ranks that share a node see the same ghosted values and so decide
    // alike; each node is counted by the owner of its first dof.
    for_each_contact_node([&](const unsigned int            node,
                              const types::global_dof_index dof0,
                              const Tensor<1, dim> &        outward) {
      if (contact.has_changed(node, 0))
        return;
      const bool counted = state.owned_dofs.is_element(dof0);
      if (contact.holds(node, 0))
        {
          // The wall force on the material is minus the out-of-balance
          // force; it pulls when it points out of the grid.
          double pull = 0.;
          for (unsigned int a = 0; a < dim; ++a)
            pull -= residual_at_nodes(dof0 + a) * outward[a];
          if (contact.release_if_pulling(node, 0, pull))
            released += counted;
        }
      else if (closing(dof0) > 0. && contact.engage(node, 0))
        engaged += counted;
    });
    released = Utilities::MPI::sum(released, comm);
    engaged  = Utilities::MPI::sum(engaged, comm);
    if (released + engaged == 0)
      return false;
    pcout << "    contact: " << released << " node(s) released, " << engaged
          << " engaged" << std::endl;
    make_constraints(state);
    return true;
  }



  template class GridSystem<2>;
  template class GridSystem<3>;
} // namespace mpm
