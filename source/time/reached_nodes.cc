#include <deal.II/base/mpi.h>

#include <mpm/points/point_layout.h>
#include <mpm/time/reached_nodes.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mpm
{
  template <int dim>
  void
  ReachedNodes<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newton");
    prm.declare_entry(
      "Weak node fraction", "0.02", Patterns::Double(0., 1.),
      "Smooth grid shape functions (Grid/Shape functions other than "
      "linear) reach nodes outside the material that carry only a sliver "
      "of it; Newton then moves them far and diverges. A node whose points "
      "weigh less than this fraction of a cell's volume (sum over points "
      "of N V) is tied to strong nodes by linear extrapolation, along a "
      "grid line (u_k = 2 u_a - u_b) or across a cell face (u_k = u_a + "
      "u_b - u_c), which keeps affine motions exact (extended B-splines, "
      "after Yamaguchi, Moutsanidis and Bazilevs 2021). 0: no ties.");
    prm.leave_subsection();
  }



  template <int dim>
  ReachedNodes<dim>::ReachedNodes(
    ParameterHandler &                              prm,
    const Grid<dim> &                               grid,
    const GridBasis<dim> &                          basis,
    const std::vector<const NodalCondition<dim> *> &conditions)
    : grid(grid)
    , basis(basis)
    , conditions(conditions)
  {
    prm.enter_subsection("Newton");
    weak_fraction = prm.get_double("Weak node fraction");
    prm.leave_subsection();
  }



  template <int dim>
  void
  ReachedNodes<dim>::find(
    const std::vector<typename ImplicitState<dim>::PointGroup> &groups,
    const std::vector<CellIterator> &                          cells)
  {
    for (auto *vector : {&reached, &support_volume})
      if (vector->get_partitioner() != grid.node_partitioner())
        vector->reinit(grid.node_partitioner());
      else
        {
          *vector = 0.;
          vector->zero_out_ghost_values();
        }
    occupied_cells.clear();
    for (const CellIterator &cell : cells)
      occupied_cells.push_back(cell->active_cell_index());
    for (const auto &group : groups)
      for (unsigned int q = 0; q < group.particles.size(); ++q)
        {
          const auto &particle = group.particles[q];
          const auto &support  = group.supports[q];
          // In the plane: a ring's or a plate's volume over its ring or
          // thickness, to compare with a cell's area.
          const double volume =
            PointLayout<dim>::current_volume(particle->get_properties()) /
            grid.geometry().out_of_plane_measure(particle->get_location());
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            {
              reached.local_element(support.nodes[i]) = 1.;
              support_volume.local_element(support.nodes[i]) +=
                support.N[i] * volume;
            }
        }
    reached.compress(VectorOperation::max);
    reached.update_ghost_values();
    support_volume.compress(VectorOperation::add);
    support_volume.update_ghost_values();
  }



  template <int dim>
  void
  ReachedNodes<dim>::tie_weak_nodes(
    const std::vector<types::global_dof_index> &node_dof,
    const types::global_dof_index               n_dofs,
    const MPI_Comm                              comm,
    ImplicitState<dim> &                        state)
  {
    if (!(weak_fraction > 0.))
      return;
    // A node is weak where its points weigh less than the fraction of a
    // cell's area (volume in 3D). Each rank proposes ties for the weak
    // nodes in the lattice patches of its cells that hold points, whose
    // nodes it sees: along a lattice line, u_k = 2 u_a - u_b, or across a
    // lattice square, u_k = u_a + u_b - u_c, with strong masters. Every
    // rank then takes, of all proposals for a node, the one whose weakest
    // master is the strongest (equal ones, to round-off, by the stencil's
    // direction, which does not depend on the numbering), so that all
    // ranks agree, and one and two ranks alike.
    const NodeLattice<dim> &lattice   = basis.node_lattice();
    const double            threshold =
      weak_fraction * grid.get_triangulation().begin_active()->measure();
    // Per proposal, by the node's first dof: worth, the stencil's
    // direction code and its masters' first dofs (the third -1 for a
    // line), as doubles for one all_gather.
    std::map<types::global_dof_index, std::array<double, 5>> proposals;
    const auto propose = [&](const unsigned int                 node,
                             const std::array<unsigned int, 3> &tie,
                             const unsigned int                 n_masters,
                             const unsigned int                 code) {
      double worth = std::numeric_limits<double>::max();
      for (unsigned int k = 0; k < n_masters; ++k)
        worth = std::min(worth, strength(tie[k]));
      if (worth < threshold)
        return;
      const std::array<double, 5> proposal = {
        {worth,
         static_cast<double>(code),
         static_cast<double>(node_dof[tie[0]]),
         static_cast<double>(node_dof[tie[1]]),
         n_masters == 3 ? static_cast<double>(node_dof[tie[2]]) : -1.}};
      auto [entry, inserted] = proposals.emplace(node_dof[node], proposal);
      if (!inserted && better(proposal, entry->second))
        entry->second = proposal;
    };
    constexpr unsigned int width = NodeLattice<dim>::patch_width;
    for (const unsigned int cell : occupied_cells)
      {
        const auto &patch = lattice.cell(cell).nodes;
        for (unsigned int j = 0; j < NodeLattice<dim>::n_patch_nodes; ++j)
          {
            const unsigned int node = patch[j];
            if (node == NodeLattice<dim>::no_node || !contains(node) ||
                !(support_volume.local_element(node) < threshold))
              continue;
            std::array<int, dim> index;
            for (unsigned int d = 0, rest = j; d < dim; ++d, rest /= width)
              index[d] = rest % width;
            // The patch node at index + the offsets, or none.
            const auto at = [&](const std::array<int, dim> &offset) {
              unsigned int k = 0, stride = 1;
              for (unsigned int d = 0; d < dim; ++d, stride *= width)
                {
                  const int i = index[d] + offset[d];
                  if (i < 0 || i >= static_cast<int>(width))
                    return NodeLattice<dim>::no_node;
                  k += i * stride;
                }
              return patch[k];
            };
            for (unsigned int d1 = 0; d1 < dim; ++d1)
              for (const int s1 : {-1, 1})
                {
                  std::array<int, dim> one{}, two{};
                  one[d1] = s1;
                  two[d1] = 2 * s1;
                  const unsigned int line = 2 * d1 + (s1 > 0);
                  propose(node, {{at(one), at(two), 0}}, 2, line);
                  for (unsigned int d2 = d1 + 1; d2 < dim; ++d2)
                    for (const int s2 : {-1, 1})
                      {
                        std::array<int, dim> other{}, both = one;
                        other[d2] = s2;
                        both[d2]  = s2;
                        propose(node,
                                {{at(one), at(other), at(both)}},
                                3,
                                2 * dim + 4 * (dim * d1 + d2) + 2 * line +
                                  (s2 > 0));
                      }
                }
          }
      }

    std::vector<double> own;
    for (const auto &[dof, proposal] : proposals)
      {
        own.push_back(static_cast<double>(dof));
        own.insert(own.end(), proposal.begin(), proposal.end());
      }
    std::map<types::global_dof_index, std::array<double, 5>> chosen;
    for (const auto &rank_proposals : Utilities::MPI::all_gather(comm, own))
      for (unsigned int t = 0; t < rank_proposals.size(); t += 6)
        {
          const auto dof =
            static_cast<types::global_dof_index>(rank_proposals[t]);
          if (!state.relevant_dofs.is_element(dof))
            continue;
          std::array<double, 5> proposal;
          std::copy(&rank_proposals[t + 1],
                    &rank_proposals[t + 6],
                    proposal.begin());
          auto [entry, inserted] = chosen.emplace(dof, proposal);
          if (!inserted && better(proposal, entry->second))
            entry->second = proposal;
        }

    // Every component's tie goes into `ties` (the sparsity pattern holds
    // them all, also where a contact wall holds the node now); the state's
    // constraints take those that no wall holds.
    masters.clear();
    masters.set_size(n_dofs);
    ties.clear();
    ties.reinit(state.relevant_dofs);
    for (const auto &[dof0, proposal] : chosen)
      for (unsigned int a = 0; a < dim; ++a)
        {
          const types::global_dof_index dof  = dof0 + a;
          const bool                    line = proposal[4] < 0.;
          const bool held = state.constraints.is_constrained(dof);
          ties.add_line(dof);
          if (!held)
            state.constraints.add_line(dof);
          for (unsigned int k = 0; k < (line ? 2u : 3u); ++k)
            {
              const auto master =
                static_cast<types::global_dof_index>(proposal[2 + k]) + a;
              const double weight =
                line ? (k == 0 ? 2. : -1.) : (k == 2 ? -1. : 1.);
              ties.add_entry(dof, master, weight);
              if (!held)
                state.constraints.add_entry(dof, master, weight);
              masters.add_index(master);
            }
        }
    ties.close();
    masters.compress();
  }



  template <int dim>
  double
  ReachedNodes<dim>::strength(const unsigned int node) const
  {
    if (node == NodeLattice<dim>::no_node || !contains(node))
      return -1.;
    // A master on a wall would chain the tie to the wall's constraint,
    // which a rank that uses the tie but does not see the master could
    // not resolve.
    for (const NodalCondition<dim> *condition : conditions)
      if (condition->acts_on(node))
        return -1.;
    return support_volume.local_element(node);
  }



  template <int dim>
  bool
  ReachedNodes<dim>::better(const std::array<double, 5> &a,
                            const std::array<double, 5> &b)
  {
    // The stronger weakest master; equal ones (to round-off, which differs
    // with the number of ranks) by the direction code.
    if (std::abs(a[0] - b[0]) > 1e-9 * std::max(a[0], b[0]))
      return a[0] > b[0];
    return a[1] < b[1];
  }



  template class ReachedNodes<2>;
  template class ReachedNodes<3>;
} // namespace mpm
