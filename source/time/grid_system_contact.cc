#include <deal.II/base/mpi.h>

#include <mpm/points/point_layout.h>
#include <mpm/time/grid_system.h>

#include <array>
#include <cmath>
#include <tuple>
#include <vector>

// The implicit grid system's contact with the walls: which nodes the
// walls hold (the gaps the points leave, the active set's decisions after
// each solve) and the reactions they keep at the end of a step. The
// constraints that follow from the set are GridSystem::make_constraints'.

namespace mpm
{
  template <int dim>
  bool
  GridSystem<dim>::at_corner(const unsigned int node) const
  {
    unsigned int n_conditions = 0, n_walls = 0;
    for (const NodalCondition<dim> *condition : conditions)
      if (condition->acts_on(node))
        {
          ++n_conditions;
          n_walls += condition->n_unilateral_walls(node);
        }
    return n_conditions > 1 || n_walls > 1;
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
    Support<dim> support;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned() || cell->active_fe_index() != 0)
          continue;
        // (vertex, wall, outward normal of the wall)
        std::vector<std::tuple<unsigned int, unsigned int,
                               const Tensor<1, dim> *>>
          contact_vertices;
        for (const unsigned int v : cell->vertex_indices())
          {
            const unsigned int node =
              grid.node_of(cell->active_cell_index(), v);
            unsigned int wall = 0;
            for (const NodalCondition<dim> *condition : conditions)
              if (condition->acts_on(node))
                for (unsigned int k = 0;
                     k < condition->n_unilateral_walls(node);
                     ++k, ++wall)
                  contact_vertices.emplace_back(
                    v, wall, &condition->unilateral_normal(node, k));
          }
        if (contact_vertices.empty())
          continue;
        // The node spacing along each axis, for on_node_stretch(); on a
        // distorted cell that of its reference directions, an estimate.
        Tensor<1, dim> spacing;
        for (unsigned int a = 0; a < dim; ++a)
          spacing[a] = cell->extent_in_direction(a);
        for (const auto &particle :
             this->points.handler().particles_in_cell(cell))
          {
            const ArrayView<const double> p = particle.get_properties();
            Point<dim>   x     = particle.get_location();
            const double reach = this->reach_of(p, x);
            if (after_solve)
              {
                basis.evaluate(cell->active_cell_index(),
                               particle.get_reference_location(),
                               p,
                               support);
                for (unsigned int i = 0; i < support.n_nodes; ++i)
                  for (unsigned int a = 0; a < dim; ++a)
                    x[a] += support.N[i] *
                            state.displacement_ghosted(
                              node_dof[support.nodes[i]] + a);
              }
            for (const auto &[v, wall, outward] : contact_vertices)
              {
                const double gap_before =
                  (cell->vertex(v) - particle.get_location()) * *outward;
                const Tensor<1, dim> to_node = cell->vertex(v) - x;
                const double         gap     = to_node * *outward;
                // A point seeded on a wall lies half its spacing from
                // it: touching, whatever the round-off of the volume.
                if (this->on_node_stretch(to_node, *outward, spacing) &&
                    gap < (1. + 1e-9) * reach &&
                    (!after_solve || gap < gap_before))
                  flags(cell->vertex_dof_index(v, 0, 0) + wall) += 1.;
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
    // released, engaged, started sliding, stopped sliding, turned (3D)
    std::vector<unsigned int> changes(5, 0);
    const TrilinosWrappers::MPI::Vector closing = contact_gaps(state, true);
    // Ranks that share a node see the same ghosted values and so decide
    // alike; each node is counted by the owner of its first dof.
    for_each_contact_node([&](const ContactPair &pair) {
      const unsigned int node = pair.node, wall = pair.wall;
      const unsigned int counted = state.owned_dofs.is_element(pair.dof0);
      if (!contact.holds(node, wall))
        {
          // An engaged node slides on as it moved along the wall in the
          // free step (the next solve sticks it where friction holds it),
          // and on a frictionless wall always.
          if (!(closing(pair.dof0 + wall) > 0.))
            return;
          const Tensor<1, dim> slide =
            sliding_increment(state, pair.dof0, pair.outward);
          const bool slides =
            pair.friction == 0. || (!std::isinf(pair.friction) &&
                                    !pair.corner && slide.norm() > 0.);
          if (contact.engage(node,
                             wall,
                             slides,
                             slide.norm() > 0. ?
                               as_direction(slide / slide.norm()) :
                               std::array<double, 3>{}))
            changes[1] += counted;
          return;
        }
      // The out-of-balance force is what the wall takes: the force of
      // the material on it. Pressing is its part along the outward normal;
      // the wall pulls where that is negative.
      Tensor<1, dim> force;
      for (unsigned int a = 0; a < dim; ++a)
        force[a] = residual_at_nodes(pair.dof0 + a);
      const double pressing = force * pair.outward;
      if (contact.release_if_pulling(node, wall, -pressing))
        {
          changes[0] += counted;
          return;
        }
      // At a corner the force along one wall is the other wall's: the
      // node sticks.
      if (!(pair.friction > 0.) || std::isinf(pair.friction) || pair.corner)
        return;
      const Tensor<1, dim>         along     = force - pressing * pair.outward;
      const std::array<double, 3> *direction =
        contact.slide_direction(node, wall);
      if (direction == nullptr)
        {
          // Stuck: it slides where the wall cannot hold the drag.
          if (along.norm() > pair.friction * pressing &&
              contact.start_sliding(node, wall,
                                    as_direction(along / along.norm())))
            changes[2] += counted;
          return;
        }
      // Sliding: it sticks where the step would take it backwards; in 3D
      // the direction follows the motion along the wall, and the step is
      // solved again with it (the tangent keeps the direction fixed).
      const Tensor<1, dim> slide =
        sliding_increment(state, pair.dof0, pair.outward);
      Tensor<1, dim> s;
      for (unsigned int a = 0; a < dim; ++a)
        s[a] = (*direction)[a];
      if (slide * s < 0.)
        {
          if (contact.stop_sliding(node, wall))
            changes[3] += counted;
        }
      else if (dim == 3 && slide.norm() > 0.)
        {
          const Tensor<1, dim> unit = slide / slide.norm();
          if ((unit - s).norm() > 1e-6)
            {
              contact.turn(node, wall, as_direction(unit));
              changes[4] += counted;
            }
        }
    },
    with_ghost_nodes());
    Utilities::MPI::sum(changes, comm, changes);
    if (changes[0] + changes[1] + changes[2] + changes[3] + changes[4] == 0)
      return false;
    pcout << "    contact: " << changes[0] << " node(s) released, "
          << changes[1] << " engaged";
    if (changes[2] + changes[3] + changes[4] > 0)
      pcout << ", " << changes[2] << " slide, " << changes[3] << " stick, "
            << changes[4] << " turn";
    pcout << std::endl;
    make_constraints(state);
    return true;
  }



  template <int dim>
  Tensor<1, dim>
  GridSystem<dim>::sliding_increment(const ImplicitState<dim> &    state,
                                     const types::global_dof_index dof0,
                                     const Tensor<1, dim> &        outward)
  {
    Tensor<1, dim> du;
    for (unsigned int a = 0; a < dim; ++a)
      du[a] = state.displacement_ghosted(dof0 + a);
    return du - (du * outward) * outward;
  }



  template <int dim>
  std::array<double, 3>
  GridSystem<dim>::as_direction(const Tensor<1, dim> &unit)
  {
    std::array<double, 3> direction{};
    for (unsigned int a = 0; a < dim; ++a)
      direction[a] = unit[a];
    return direction;
  }



  template <int dim>
  void
  GridSystem<dim>::finish_step(const ImplicitState<dim> &state)
  {
    contact.mark_started();
    for (const NodalCondition<dim> *condition : conditions)
      condition->reset_reactions();
    if (!has_active_set())
      return;
    const TrilinosWrappers::MPI::Vector residual_at_nodes =
      state.wall_reactions(this->points.get_communicator());
    // Every rank that reports a node hears its force: with the ghost
    // cells, each node of an owned or ghost cell that holds points. A
    // node on one wall gives it the whole force; one on several (a
    // corner, also with a fixed or slip wall) gives each unilateral wall
    // its part along the wall's normal.
    for_each_contact_node(
      [&](const ContactPair &pair) {
        if (!contact.holds(pair.node, pair.wall))
          return;
        Tensor<1, dim> force;
        for (unsigned int a = 0; a < dim; ++a)
          force[a] = residual_at_nodes(pair.dof0 + a);
        pair.condition.record_reaction(
          pair.node,
          pair.k,
          pair.corner ? (force * pair.outward) * pair.outward : force);
      },
      true);
  }



  // The class is instantiated in grid_system.cc; the members of this file
  // here.
#define MPM_INSTANTIATE(dim)                                                \
  template bool GridSystem<dim>::at_corner(const unsigned int) const;       \
  template TrilinosWrappers::MPI::Vector GridSystem<dim>::contact_gaps(     \
    const ImplicitState<dim> &, const bool) const;                          \
  template bool GridSystem<dim>::update_active_set(ImplicitState<dim> &);   \
  template Tensor<1, dim> GridSystem<dim>::sliding_increment(               \
    const ImplicitState<dim> &,                                             \
    const types::global_dof_index,                                          \
    const Tensor<1, dim> &);                                                \
  template std::array<double, 3> GridSystem<dim>::as_direction(             \
    const Tensor<1, dim> &);                                                \
  template void GridSystem<dim>::finish_step(const ImplicitState<dim> &);

  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace mpm
