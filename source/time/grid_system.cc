#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/vector.h>

#include <mpm/base/input_error.h>
#include <mpm/time/grid_system.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>

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
      "et al. do, and so do the smooth shape functions and an adaptive "
      "grid once it has hanging vertices.");
    prm.leave_subsection();
    ReachedNodes<dim>::declare_parameters(prm);
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
    , reached_nodes(prm, grid, basis, conditions)
  {
    prm.enter_subsection("Newton");
    scale_full_cells = prm.get("Integration") == "full cells by cell volume";
    prm.leave_subsection();
    // The basis's nodes carry the displacement; cells without points none.
    fe_collection.push_back(FESystem<dim>(*basis.node_element(), dim));
    fe_collection.push_back(FESystem<dim>(FE_Nothing<dim>(), dim));
    const auto coordinates = [&grid](const unsigned int node) {
      std::array<double, 3> x = {};
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = grid.node_position(node)[d];
      return x;
    };
    // Only the pairs this rank kept up in the last step: a rank whose cells
    // emptied still holds the pairs it last saw, which the rank that goes
    // on visiting them may have let go.
    // After a first change the set holds only such pairs, renumbered.
    grid_changing = grid.before_change.connect([this, coordinates]() {
      contact_by_position = contact.by_position(
        coordinates, [this](const unsigned int node, const unsigned int wall) {
          return !pairs_in_step_current ||
                 pairs_in_step.count({node, wall}) > 0;
        });
      pairs_in_step_current = false;
    });
    grid_changed = grid.changed.connect([this, &grid, coordinates]() {
      // The nodes are vertices of the grid, so their coordinates match to
      // the bit.
      std::map<std::array<double, 3>, unsigned int> node_at;
      for (unsigned int node = 0; node < grid.n_nodes(); ++node)
        node_at.emplace(coordinates(node), node);
      contact.renumber(Utilities::MPI::all_gather(grid.get_communicator(),
                                                  contact_by_position),
                       [&](const std::array<double, 3> &x) {
                         const auto found = node_at.find(x);
                         return found == node_at.end() ?
                                  numbers::invalid_unsigned_int :
                                  found->second;
                       });
      contact_by_position.clear();
    });
  }



  template <int dim>
  void
  GridSystem<dim>::setup(ImplicitState<dim> &state)
  {
    contact.begin_step();
    // Unknowns only on the nodes that carry points: those of the cells
    // that hold points (Q1), or, for shape functions that reach the cells
    // around, of every cell with a node a point reaches (the nodes of
    // those cells that no point reaches are held at zero).
    collect_cell_groups(state);
    if (supports_leave_cell())
      reached_nodes.find(state.groups, group_cells);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          bool carries = this->points.handler().n_particles_in_cell(cell) > 0;
          if (supports_leave_cell())
            for (const unsigned int v : cell->vertex_indices())
              carries =
                carries || reached_nodes.contains(
                             grid.node_of(cell->active_cell_index(), v));
          cell->set_active_fe_index(carries ? 0 : 1);
        }
    dof_handler.distribute_dofs(fe_collection);
    state.owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, state.relevant_dofs);
    number_node_dofs();
    number_cell_groups(state);

    // Contact nodes stay engaged into the new step only while material
    // still touches them. The first step holds every node that material
    // touches, so that a body put on a wall rests on it from the first
    // solve (a quasi-static step needs it); its solve releases those that
    // pull. Later steps engage where material closes on a wall.
    if (has_active_set())
      {
        const TrilinosWrappers::MPI::Vector touching =
          contact_gaps(state, false);
        const bool first_step = !contact.has_started();
        pairs_in_step.clear();
        pairs_in_step_current = true;
        for_each_contact_node(
          [&](const ContactPair &pair) {
            pairs_in_step.insert({pair.node, pair.wall});
            if (touching(pair.dof0 + pair.wall) == 0.)
              contact.let_go(pair.node, pair.wall);
            else if (first_step)
              contact.hold_from_start(pair.node,
                                      pair.wall,
                                      pair.friction == 0.);
          },
          with_ghost_nodes());
      }
    make_constraints(state);

    const MPI_Comm comm = this->points.get_communicator();
    // Rows for the masters of tied nodes too, which may lie beyond this
    // rank's ghost cells.
    IndexSet        rows = state.relevant_dofs;
    const IndexSet &tie_masters = reached_nodes.tie_masters();
    if (tie_masters.size() == rows.size())
      rows.add_indices(tie_masters);
    DynamicSparsityPattern dsp(rows);
    // Every pair of nodes that share a point couples. Constrained rows
    // keep their entries, and every component's tie is in, so that
    // releasing a contact node (whose component may then be tied) needs
    // no new pattern.
    const AffineConstraints<double> &ties = reached_nodes.tie_constraints();
    for (const auto &group : state.groups)
      {
        state.constraints.add_entries_local_to_global(group.dofs, dsp, true);
        if (ties.n_constraints() > 0)
          ties.add_entries_local_to_global(group.dofs, dsp, true);
      }
    for (const types::global_dof_index dof0 : state.unreached_node_dofs)
      for (unsigned int a = 0; a < dim; ++a)
        dsp.add(dof0 + a, dof0 + a);
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               state.owned_dofs,
                                               comm,
                                               rows);
    state.reinit(dsp, comm);
  }



  template <int dim>
  void
  GridSystem<dim>::number_node_dofs()
  {
    node_dof.assign(grid.n_nodes(), numbers::invalid_dof_index);
    for_each_unknown_vertex(
      [&](const auto &cell, const unsigned int v, const unsigned int node) {
        node_dof[node] = cell->vertex_dof_index(v, 0, 0);
      },
      true);
  }



  template <int dim>
  void
  GridSystem<dim>::collect_cell_groups(ImplicitState<dim> &state)
  {
    unsigned int n_groups = 0;
    group_cells.clear();
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned() ||
            this->points.handler().n_particles_in_cell(cell) == 0)
          continue;
        group_cells.push_back(cell);
        auto &group = state.next_group(n_groups);
        group.supports.resize(this->points.handler().n_particles_in_cell(cell));
        unsigned int q = 0;
        const auto cell_points = this->points.handler().particles_in_cell(cell);
        for (auto particle = cell_points.begin(); particle != cell_points.end();
             ++particle, ++q)
          {
            group.particles.push_back(particle);
            basis.evaluate(cell->active_cell_index(),
                           particle->get_reference_location(),
                           particle->get_properties(),
                           group.supports[q]);
          }
      }
    state.groups.resize(n_groups);
  }



  template <int dim>
  void
  GridSystem<dim>::number_cell_groups(ImplicitState<dim> &state) const
  {
    // A group's nodes are those its points reach, in the order met (for Q1
    // the cell's vertices); each point's support is spread over them, with
    // zeros at the nodes it does not reach.
    std::vector<unsigned int> nodes;
    Support<dim>              own;
    for (unsigned int g = 0; g < state.groups.size(); ++g)
      {
        auto &group  = state.groups[g];
        group.weight = quadrature_scale(group_cells[g]);
        nodes.clear();
        for (const Support<dim> &support : group.supports)
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            if (std::find(nodes.begin(), nodes.end(), support.nodes[i]) ==
                nodes.end())
              nodes.push_back(support.nodes[i]);
        group.dofs.resize(nodes.size() * dim);
        for (unsigned int i = 0; i < nodes.size(); ++i)
          for (unsigned int a = 0; a < dim; ++a)
            group.dofs[i * dim + a] = node_dof[nodes[i]] + a;
        for (Support<dim> &support : group.supports)
          {
            if (support.n_nodes == nodes.size() &&
                std::equal(nodes.begin(), nodes.end(), support.nodes.begin()))
              continue;
            own = support;
            support.resize(nodes.size());
            for (unsigned int i = 0; i < nodes.size(); ++i)
              {
                support.nodes[i]  = nodes[i];
                support.N[i]      = 0.;
                support.grad_N[i] = Tensor<1, dim>();
              }
            for (unsigned int j = 0; j < own.n_nodes; ++j)
              {
                const unsigned int i =
                  std::find(nodes.begin(), nodes.end(), own.nodes[j]) -
                  nodes.begin();
                support.N[i]      = own.N[j];
                support.grad_N[i] = own.grad_N[j];
              }
          }
      }
  }



  template <int dim>
  double
  GridSystem<dim>::quadrature_scale(
    const typename DoFHandler<dim>::active_cell_iterator &cell) const
  {
    // Smooth shape functions reach beyond the cell: the cell is not their
    // domain of integration; nor is it on an adapted grid, where a face
    // neighbour may be a refined one.
    if (!scale_full_cells || supports_leave_cell())
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
        // In plane stress the points' volumes at their initial thickness:
        // the cell holds them at their own thickness.
        volume += grid.geometry().volume_at_initial_thickness(
          Layout::current_volume(p),
          dim == 2 ? p[Layout::out_of_plane_stretch] : 1.);
      }
    // The cell's volume: in axisymmetry the ring it sweeps, 2 pi x_c A at
    // its centroid x_c (Pappus); in plane stress A h_0.
    return cell->measure() *
             grid.geometry().out_of_plane_measure(cell->barycenter()) /
           volume;
  }



  template <int dim>
  void
  GridSystem<dim>::make_constraints(ImplicitState<dim> &state)
  {
    // Grid conditions on the nodes of active cells: a wall along an axis
    // fixes that component; a slanted wall ties the components so that the
    // normal displacement vanishes.
    state.constraints.clear();
    state.constraints.reinit(state.relevant_dofs);
    state.sliding_nodes.clear();
    bool              unsupported_corner = false;
    std::vector<Hold> holds;
    // A node is met once per cell around it.
    std::set<std::pair<unsigned int, unsigned int>> slides_found;
    const auto first_visit = [&](const unsigned int node,
                              const unsigned int wall) {
      return slides_found.insert({node, wall}).second;
    };
    for_each_constrained_vertex([&](const auto &               cell,
                                    const unsigned int         v,
                                    const unsigned int         node,
                                    const NodalCondition<dim> &condition,
                                    const unsigned int         first_wall) {
      std::array<types::global_dof_index, dim> dofs;
      for (unsigned int a = 0; a < dim; ++a)
        dofs[a] = cell->vertex_dof_index(v, a, 0);
      holds.resize(condition.n_unilateral_walls(node));
      for (unsigned int k = 0; k < holds.size(); ++k)
        {
          const unsigned int wall = first_wall + k;
          const std::array<double, 3> *direction =
            contact.slide_direction(node, wall);
          holds[k] = !contact.holds(node, wall) ? Hold::free :
                     direction != nullptr       ? Hold::slip :
                                                  Hold::stick;
          const double friction = condition.friction_coefficient(node, k);
          if (holds[k] == Hold::slip && friction > 0. &&
              first_visit(node, wall))
            {
              typename ImplicitState<dim>::SlidingNode sliding;
              sliding.outward  = condition.unilateral_normal(node, k);
              sliding.friction = friction;
              for (unsigned int a = 0; a < dim; ++a)
                sliding.direction[a] = (*direction)[a];
              state.sliding_nodes.emplace(dofs[0], sliding);
            }
        }
      if (!condition.add_constraints(
            node, dofs, holds.data(), state.constraints))
        unsupported_corner = true;
    },
    with_ghost_nodes());
    // Decided on all ranks together, so that all stop.
    if (basis.reaches_neighbours())
      reached_nodes.tie_weak_nodes(node_dof,
                                   dof_handler.n_dofs(),
                                   this->points.get_communicator(),
                                   state);

    // Nodes of cells with unknowns that no point reaches carry nothing:
    // held at zero (so are hanging vertices, which the supports condense).
    state.unreached_node_dofs.clear();
    if (supports_leave_cell())
      {
        // A node is met once per cell around it.
        std::vector<bool> met(grid.n_nodes(), false);
        for_each_unknown_vertex(
          [&](const auto &, const unsigned int, const unsigned int node) {
            if (reached_nodes.contains(node) || met[node])
              return;
            met[node]                          = true;
            const types::global_dof_index dof0 = node_dof[node];
            for (unsigned int a = 0; a < dim; ++a)
              if (!state.constraints.is_constrained(dof0 + a))
                state.constraints.add_line(dof0 + a);
            if (state.owned_dofs.is_element(dof0))
              state.unreached_node_dofs.push_back(dof0);
          },
          true);
      }
    if (Utilities::MPI::logical_or(unsupported_corner,
                                   this->points.get_communicator()))
      throw RunError("Boundary conditions: the implicit schemes support "
                     "corners between slip or friction walls only when the "
                     "walls are aligned with the axes, and material reached "
                     "such a corner.");
    state.constraints.close();
  }



  template class GridSystem<2>;
  template class GridSystem<3>;
} // namespace mpm
