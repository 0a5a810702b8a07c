#include <deal.II/base/mpi.h>
#include <deal.II/lac/sparsity_tools.h>

#include <mpm/base/input_error.h>
#include <mpm/time/cloud_system.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>

namespace mpm
{
  template <int dim>
  CloudSystem<dim>::CloudSystem(MaterialPoints<dim> &               points,
                                const Grid<dim> &                   grid,
                                const DirichletConditions<dim> &    dirichlet,
                                std::unique_ptr<MeshfreeBasis<dim>> meshfree,
                                const Newmark &                     newmark,
                                ConditionalOStream &                pcout,
                                TimerOutput &                       timer)
    : ImplicitSystem<dim>(points)
    , meshfree(std::move(meshfree))
    , cloud(points, grid, dirichlet)
    , newmark(newmark)
    , pcout(pcout)
    , timer(timer)
  {}



  template <int dim>
  void
  CloudSystem<dim>::setup(ImplicitState<dim> &state)
  {
    cloud.held_by_walls.begin_step();
    // A point whose shape functions cannot be built stops the run on
    // every rank, with its message.
    std::string failure;
    {
      TimerOutput::Scope t(timer, "meshfree shape functions");
      meshfree->reinit(cloud.positions);
      unsigned int n_groups = 0;
      for (auto particle = this->points.handler().begin();
           particle != this->points.handler().end();
           ++particle)
        {
          auto &group = state.next_group(n_groups);
          group.particles.push_back(particle);
          group.supports.resize(1);
          Support<dim> &support = group.supports[0];
          try
            {
              meshfree->evaluate(particle->get_location(), support);
            }
          catch (const RunError &e)
            {
              failure = "Material point " +
                        std::to_string(particle->get_id()) + ": " + e.what();
              break;
            }
          group.dofs.resize(support.n_nodes * dim);
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            for (unsigned int a = 0; a < dim; ++a)
              group.dofs[i * dim + a] = support.nodes[i] * dim + a;
        }
      state.groups.resize(n_groups);
    }
    const MPI_Comm comm = this->points.get_communicator();
    if (Utilities::MPI::logical_or(!failure.empty(), comm))
      for (const std::string &message : Utilities::MPI::all_gather(comm, failure))
        if (!message.empty())
          throw RunError(message, false);
    // MLS shape functions can be negative: a lumped nodal mass must still
    // be positive.
    if (state.dynamic && newmark.lumped_mass &&
        meshfree->kind() == MeshfreeBasis<dim>::Kind::mls)
      {
        std::vector<double> nodal_mass(cloud.size(), 0.);
        for (const auto &group : state.groups)
          for (unsigned int k = 0; k < group.supports[0].n_nodes; ++k)
            nodal_mass[group.supports[0].nodes[k]] +=
              group.supports[0].N[k] *
              group.particles[0]->get_properties()[PointLayout<dim>::mass];
        Utilities::MPI::sum(nodal_mass, comm, nodal_mass);
        for (unsigned int i = 0; i < cloud.size(); ++i)
          if (nodal_mass[i] < 0.)
            throw RunError("Node " + std::to_string(i) + " at (" +
                             Utilities::to_string(cloud.positions[i][0]) +
                             ", ...) has a negative lumped MLS mass; use "
                             "Newmark/Mass matrix = consistent, or "
                             "Method = GMM-LME.",
                           false);
      }
    // Every rank holds the whole cloud (NodeCloud). A node's unknowns
    // belong to the lowest rank whose points reach it, so that a rank
    // writes into other ranks' rows only near the partition's boundary;
    // a node that no point reaches belongs to rank 0.
    const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    reaching_rank.assign(cloud.size(), n_ranks);
    for (const auto &group : state.groups)
      for (unsigned int k = 0; k < group.supports[0].n_nodes; ++k)
        reaching_rank[group.supports[0].nodes[k]] = rank;
    Utilities::MPI::min(reaching_rank, comm, reaching_rank);
    state.owned_dofs = IndexSet(cloud.size() * dim);
    for (unsigned int i = 0; i < cloud.size(); ++i)
      if (reaching_rank[i] == rank || (reaching_rank[i] == n_ranks && rank == 0))
        state.owned_dofs.add_range(i * dim, (i + 1) * dim);
    state.owned_dofs.compress();
    state.relevant_dofs = complete_index_set(cloud.size() * dim);
    make_constraints(state);
    DynamicSparsityPattern dsp = sparsity_pattern(state);
    state.reinit(dsp, comm);
  }



  template <int dim>
  void
  CloudSystem<dim>::project_initial_conditions(ImplicitState<dim> &state)
  {
    if (!cloud.has_history)
      {
        ImplicitSystem<dim>::project_initial_conditions(state);
        return;
      }
    // GMM nodes carry their own velocity and acceleration ([I] Algorithm
    // 2); only the first step takes them from the points.
    const MPI_Comm comm = this->points.get_communicator();
    state.projected_velocity.reinit(state.owned_dofs, comm);
    state.projected_acceleration.reinit(state.owned_dofs, comm);
    for (const types::global_dof_index dof : state.owned_dofs)
      {
        const unsigned int i = dof / dim, a = dof % dim;
        state.projected_velocity(dof)     = cloud.velocities[i][a];
        state.projected_acceleration(dof) = cloud.accelerations[i][a];
      }
    state.projected_velocity.compress(VectorOperation::insert);
    state.projected_acceleration.compress(VectorOperation::insert);
    state.constrain_initial_conditions();
  }



  template <int dim>
  DynamicSparsityPattern
  CloudSystem<dim>::sparsity_pattern(const ImplicitState<dim> &state) const
  {
    DynamicSparsityPattern dsp(state.relevant_dofs);
    for (const auto &group : state.groups)
      state.constraints.add_entries_local_to_global(group.dofs, dsp, true);
    for (const types::global_dof_index dof0 : state.unreached_node_dofs)
      for (unsigned int a = 0; a < dim; ++a)
        dsp.add(dof0 + a, dof0 + a);
    // The rows of other ranks' nodes that this rank's points reach.
    SparsityTools::distribute_sparsity_pattern(dsp,
                                               state.owned_dofs,
                                               this->points.get_communicator(),
                                               state.relevant_dofs);
    return dsp;
  }



  template <int dim>
  void
  CloudSystem<dim>::make_constraints(ImplicitState<dim> &state)
  {
    state.constraints.clear();
    state.constraints.reinit(state.relevant_dofs);
    const unsigned int n_nodes = cloud.size();
    std::vector<std::array<bool, dim>> held(n_nodes);
    for (unsigned int i = 0; i < n_nodes; ++i)
      held[i] = cloud.held_components(i);
    // A node that no point reaches has no stiffness and no mass: it stays
    // where it is, which keeps the matrix regular.
    const unsigned int n_ranks =
      Utilities::MPI::n_mpi_processes(this->points.get_communicator());
    state.unreached_node_dofs.clear();
    for (unsigned int i = 0; i < n_nodes; ++i)
      if (reaching_rank[i] == n_ranks)
        {
          for (unsigned int a = 0; a < dim; ++a)
            state.constraints.add_line(i * dim + a);
          held[i].fill(false);
          // The owner alone puts the unit on its diagonal.
          if (state.owned_dofs.is_element(i * dim))
            state.unreached_node_dofs.push_back(i * dim);
        }

    if (meshfree->kind() == MeshfreeBasis<dim>::Kind::lme)
      {
        for (unsigned int i = 0; i < n_nodes; ++i)
          for (unsigned int a = 0; a < dim; ++a)
            if (held[i][a])
              state.constraints.add_line(i * dim + a);
        state.constraints.close();
        return;
      }

    // MLS, per component a: sum_j N_j(x_d) u_j = 0 at each held node d.
    // With D the held nodes and F the others, A_DD u_D = -A_DF u_F, so
    // u_D = C u_F with C = -A_DD^-1 A_DF, a dense solve of the size of D.
    // The shape functions at every node that holds a component.
    // Every rank builds them alike; the first counts the evaluations.
    const auto counts_before = meshfree->statistics();
    std::map<unsigned int, Support<dim>> support_at;
    for (unsigned int i = 0; i < n_nodes; ++i)
      if (std::find(held[i].begin(), held[i].end(), true) != held[i].end())
        try
          {
            meshfree->evaluate(cloud.positions[i], support_at[i]);
          }
        catch (const RunError &e)
          {
            throw RunError("The MLS wall condition at node " +
                             std::to_string(i) + ": " + e.what(),
                           false);
          }
    if (Utilities::MPI::this_mpi_process(this->points.get_communicator()) != 0)
      meshfree->set_statistics(counts_before);
    for (unsigned int a = 0; a < dim; ++a)
      {
        std::vector<unsigned int>           held_nodes;
        std::map<unsigned int, unsigned int> row_of;
        for (unsigned int i = 0; i < n_nodes; ++i)
          if (held[i][a])
            {
              row_of[i] = held_nodes.size();
              held_nodes.push_back(i);
            }
        if (held_nodes.empty())
          continue;
        const unsigned int                   n_held = held_nodes.size();
        std::map<unsigned int, unsigned int> column_of;
        std::vector<unsigned int>            free_nodes;
        Eigen::MatrixXd A_DD = Eigen::MatrixXd::Zero(n_held, n_held);
        std::vector<std::vector<std::pair<unsigned int, double>>> A_DF(n_held);
        for (unsigned int r = 0; r < n_held; ++r)
          {
            const Support<dim> &support = support_at[held_nodes[r]];
            for (unsigned int k = 0; k < support.n_nodes; ++k)
              {
                const unsigned int j = support.nodes[k];
                if (const auto held_j = row_of.find(j); held_j != row_of.end())
                  A_DD(r, held_j->second) = support.N[k];
                else
                  {
                    const auto [it, added] =
                      column_of.emplace(j, free_nodes.size());
                    if (added)
                      free_nodes.push_back(j);
                    A_DF[r].emplace_back(it->second, support.N[k]);
                  }
              }
          }
        Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n_held, free_nodes.size());
        for (unsigned int r = 0; r < n_held; ++r)
          for (const auto &[c, value] : A_DF[r])
            B(r, c) = value;
        const Eigen::FullPivLU<Eigen::MatrixXd> lu(A_DD);
        if (!lu.isInvertible())
          throw RunError("The MLS boundary conditions cannot be imposed: the "
                         "shape functions of the held nodes at their own "
                         "positions are linearly dependent.",
                         false);
        const Eigen::MatrixXd C = -lu.solve(B);
        // A_DD^-1 is dense, but decays fast away from a held node: entries
        // below 1e-9 of a row's largest tie a held node to distant nodes
        // for nothing but fill (at the column's floor they made assembly
        // ten times slower). Dropping them leaves the condition holding
        // to 1e-9 of the nodal values.
        for (unsigned int r = 0; r < n_held; ++r)
          {
            const types::global_dof_index row = held_nodes[r] * dim + a;
            const double cut =
              free_nodes.empty() ? 0. : 1e-9 * C.row(r).cwiseAbs().maxCoeff();
            state.constraints.add_line(row);
            for (unsigned int c = 0; c < free_nodes.size(); ++c)
              if (std::abs(C(r, c)) > cut)
                state.constraints.add_entry(row,
                                            free_nodes[c] * dim + a,
                                            C(r, c));
          }
      }
    state.constraints.close();
  }



  template <int dim>
  bool
  CloudSystem<dim>::update_active_set(ImplicitState<dim> &state)
  {
    const MPI_Comm                      comm = this->points.get_communicator();
    const TrilinosWrappers::MPI::Vector residual_at_nodes =
      state.wall_reactions(comm);
    unsigned int released = 0, engaged = 0;
    // A node held by a contact wall lets go when the wall pulls. As on
    // the grid, a point that the step brings within half its spacing
    // of a wall, moving towards it, engages the nodes next to it that
    // stand for the stretch of the wall it touches (on_node_stretch) and
    // lie within that distance of the wall or beyond it.
    // The cloud's outer nodes reach a wall before the material does,
    // so the nodes alone cannot tell; and a held node far from the
    // material would be a pivot that levers the body off the wall.
    // Every rank holds the whole cloud and the whole residual, so every
    // rank releases the same pairs; the pairs that each rank's points
    // engage are then applied everywhere in the order of the ranks.
    // A node may be held by several walls (at a corner); the active set
    // changes each (node, wall) pair at most once per step.
    const unsigned int n_walls = cloud.walls.size();
    for (unsigned int i = 0; i < cloud.size(); ++i)
      for (unsigned int w = 0; w < n_walls; ++w)
        {
          if (!cloud.is_held_by(i, w) ||
              cloud.walls[w].kind !=
                DirichletConditions<dim>::WallKind::contact)
            continue;
          double pull = 0.;
          for (unsigned int a = 0; a < dim; ++a)
            pull -= residual_at_nodes(i * dim + a) *
                    cloud.walls[w].outward[a];
          released += cloud.held_by_walls.release_if_pulling(i, w, pull);
        }
    std::vector<unsigned int> to_engage;
    Tensor<1, dim>            spacing;
    for (unsigned int a = 0; a < dim; ++a)
      spacing[a] = cloud.spacing();
    for (const auto &group : state.groups)
      {
        const Support<dim> &support = group.supports[0];
        const Point<dim> x_old = group.particles[0]->get_location();
        const double     reach =
          this->reach_of(group.particles[0]->get_properties(), x_old);
        Point<dim>       x_new = x_old;
        for (unsigned int k = 0; k < support.n_nodes; ++k)
          for (unsigned int a = 0; a < dim; ++a)
            x_new[a] += support.N[k] *
                        state.displacement_ghosted(group.dofs[k * dim + a]);
        for (unsigned int w = 0; w < cloud.walls.size(); ++w)
          {
            const auto & c       = cloud.walls[w];
            const double gap_new = c.offset - c.outward * x_new;
            if (!(gap_new < reach && gap_new < c.offset - c.outward * x_old))
              continue;
            for (unsigned int k = 0; k < support.n_nodes; ++k)
              {
                const unsigned int node = support.nodes[k];
                const Point<dim> &x_node = cloud.positions[node];
                if (c.offset - c.outward * x_node < reach &&
                    this->on_node_stretch(x_node - x_new,
                                          c.outward,
                                          spacing))
                  {
                    to_engage.push_back(node);
                    to_engage.push_back(w);
                  }
              }
          }
      }
    for (const std::vector<unsigned int> &pairs :
         Utilities::MPI::all_gather(comm, to_engage))
      for (unsigned int k = 0; k < pairs.size(); k += 2)
        engaged += cloud.held_by_walls.engage(pairs[k], pairs[k + 1]);
    if (released + engaged == 0)
      return false;
    pcout << "    walls: " << released << " node(s) released, " << engaged
          << " held" << std::endl;
    // MLS ties newly held nodes to their neighbours: new entries.
    make_constraints(state);
    state.factorization.reset();
    state.tangent.reinit(state.owned_dofs,
                         state.owned_dofs,
                         sparsity_pattern(state),
                         this->points.get_communicator());
    return true;
  }



  template <int dim>
  void
  CloudSystem<dim>::finish_step(const ImplicitState<dim> &state)
  {
    for (unsigned int i = 0; i < cloud.size(); ++i)
      {
        const std::array<bool, dim> held = cloud.held_components(i);
        Tensor<1, dim>              du, v, a;
        for (unsigned int d = 0; d < dim; ++d)
          {
            du[d] = state.displacement_ghosted(i * dim + d);
            v[d]  = state.velocity_ghosted(i * dim + d);
            a[d]  = state.acceleration_ghosted(i * dim + d);
          }
        // MLS nodal values are not displacements at the node; a held node
        // stays on its wall.
        for (unsigned int d = 0; d < dim; ++d)
          if (!held[d])
            cloud.positions[i][d] += du[d];
        if (state.dynamic)
          {
            const Tensor<1, dim> a_new =
              newmark.end_acceleration(du, v, a, state.time_step);
            cloud.velocities[i] =
              v + newmark.velocity_increment(a, a_new, state.time_step);
            cloud.accelerations[i] = a_new;
          }
      }
    cloud.has_history = true;
  }



  template class CloudSystem<2>;
  template class CloudSystem<3>;
} // namespace mpm
