#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <Epetra_CrsMatrix.h>

#include <mpm/assembly/point_assembly.h>
#include <mpm/core/input_error.h>
#include <mpm/time/implicit_integrator.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <iomanip>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  ImplicitIntegrator<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newton");
    prm.declare_entry("Tolerance", "1e-8", Patterns::Double(0.),
                      "Convergence when the out-of-balance force ratio "
                      "alpha = |f_ext - f_int| / |f_ext| (Beuth et al. eq. "
                      "31) falls below this.");
    prm.declare_entry("Maximum iterations", "25", Patterns::Integer(1),
                      "Iterations before a load step counts as failed and "
                      "is cut in half.");
    prm.declare_entry("Variant", "full",
                      Patterns::Selection("full|modified|linear"),
                      "full: a new tangent every iteration (quadratic "
                      "convergence). modified: the tangent of the step's "
                      "first iteration throughout, as in Beuth et al., "
                      "factorised once by the direct solvers (linear "
                      "convergence, cheap iterations). "
                      "linear: one iteration per load step, accepted as it "
                      "is; with one load step this is the small-strain "
                      "linear solution.");
    prm.declare_entry("Line search", "false", Patterns::Bool(),
                      "Backtrack along each Newton correction, halving it "
                      "up to 5 times, until the out-of-balance force falls. "
                      "For plastic runs in which points switch between the "
                      "planes, edges and apex of Mohr-Coulomb and full "
                      "Newton cycles. Each halving costs one more "
                      "assembly; the trial kept is the next iterate and is "
                      "not assembled again.");
    prm.declare_entry("Check tangent", "false", Patterns::Bool(),
                      "At each assembly of the tangent K, compare K d with "
                      "central differences of the out-of-balance force r "
                      "along a fixed pseudo-random direction d of size "
                      "3e-9 times the smallest cell (within the "
                      "constraints), and print |K d + (r(u + d) - r(u - "
                      "d)) / 2| / |K d| over the unconstrained rows: about "
                      "5e-8 (round-off) for a consistent tangent. A point "
                      "within d of a kink of its yield surface gives an "
                      "isolated larger value. For checking a new material "
                      "law or condition; costs two assemblies of the force "
                      "per check.");
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
    prm.declare_entry("Linear solver", "direct",
                      Patterns::Selection("direct|MUMPS|CG-AMG"),
                      "direct: sparse LU (KLU through Trilinos Amesos), for "
                      "small problems. MUMPS: the multifrontal sparse LU of "
                      "MUMPS (Amesos), faster on the wider patterns of the "
                      "meshfree methods (6 times on the column collapse "
                      "with GMM-LME at h = 0.05, with OpenBLAS) and on large "
                      "MPM grids (1.9 times on the column at h = 0.025, "
                      "51 200 points); as fast on small MPM grids. "
                      "CG-AMG: conjugate gradients with "
                      "Trilinos ML algebraic multigrid, for large problems "
                      "with a symmetric tangent (not for non-associated "
                      "plasticity).");
    prm.leave_subsection();

    prm.enter_subsection("Newmark");
    prm.declare_entry("Bossak alpha", "0", Patterns::Double(-0.5, 0.),
                      "Bossak's alpha_B: the inertia is taken at "
                      "(1 - alpha_B) a_n+1 + alpha_B a_n, which damps high "
                      "frequencies. 0 is plain Newmark; -0.3 to -0.1 are "
                      "usual.");
    prm.declare_entry("Beta", "auto", Patterns::Anything(),
                      "Newmark beta. auto: (1 - alpha_B)^2 / 4, that is 0.25 "
                      "for plain Newmark (the trapezoidal rule, no numerical "
                      "damping).");
    prm.declare_entry("Gamma", "auto", Patterns::Anything(),
                      "Newmark gamma. auto: 1/2 - alpha_B.");
    prm.declare_entry("Mass matrix", "consistent",
                      Patterns::Selection("consistent|lumped"),
                      "consistent: the inertia m_p a(x_p) of each point, "
                      "with mass m_p N_i N_k (Iaconeta et al. eq. 30). "
                      "lumped: the nodal masses sum_p m_p N_i on the "
                      "diagonal, as the explicit scheme uses. A node reached "
                      "by only one or two points has a nearly singular "
                      "consistent mass and stiffness; the lumped mass keeps "
                      "Newton robust on fast-moving bodies with thin "
                      "surface cells.");
    prm.leave_subsection();
  }



  template <int dim>
  ImplicitIntegrator<dim>::ImplicitIntegrator(
    const bool                                    dynamic,
    ParameterHandler &                            prm,
    MaterialPoints<dim> &                         points,
    const Grid<dim> &                             grid,
    const GridBasis<dim> &                        basis,
    const DirichletConditions<dim> &              dirichlet,
    const std::vector<std::unique_ptr<Material>> &materials,
    const Tensor<1, dim> &                        gravity,
    ConditionalOStream &                          pcout,
    TimerOutput &                                 timer,
    std::unique_ptr<MeshfreeBasis<dim>>           meshfree_basis)
    : points(points)
    , grid(grid)
    , basis(basis)
    , dirichlet(dirichlet)
    , materials(materials)
    , gravity(gravity)
    , pcout(pcout)
    , timer(timer)
    , dynamic(dynamic)
    , meshfree(std::move(meshfree_basis))
    , dof_handler(points.get_triangulation())
  {
    if (meshfree)
      cloud = std::make_unique<NodeCloud<dim>>(points, grid, dirichlet);
    prm.enter_subsection("Newton");
    tolerance       = prm.get_double("Tolerance");
    max_iterations  = prm.get_integer("Maximum iterations");
    modified_newton = prm.get("Variant") == "modified";
    linear_only     = prm.get("Variant") == "linear";
    line_search     = prm.get_bool("Line search");
    check_tangent   = prm.get_bool("Check tangent");
    if (line_search && linear_only)
      throw InputError("Newton/Line search does not go with Variant = "
                       "linear, which accepts its one iteration as it is.");
    linear_solver   = prm.get("Linear solver");
    scale_full_cells = prm.get("Integration") == "full cells by cell volume";
    prm.leave_subsection();
    if (!(tolerance > 0.))
      throw InputError("Newton/Tolerance must be positive.");
    prm.enter_subsection("Newmark");
    bossak_alpha = prm.get_double("Bossak alpha");
    auto number_or_auto = [&](const std::string &entry, const double automatic) {
      const std::string text = prm.get(entry);
      if (text == "auto")
        return automatic;
      try
        {
          std::size_t used  = 0;
          const double value = std::stod(text, &used);
          if (used == text.size())
            return value;
        }
      catch (const std::exception &)
        {}
      throw InputError("Newmark/" + entry + " = '" + text +
                       "' must be a number or 'auto'.");
    };
    beta =
      number_or_auto("Beta", 0.25 * (1. - bossak_alpha) * (1. - bossak_alpha));
    gamma = number_or_auto("Gamma", 0.5 - bossak_alpha);
    lumped_mass = prm.get("Mass matrix") == "lumped";
    prm.leave_subsection();
    if (dynamic && !(beta > 0.))
      throw InputError("Newmark/Beta must be positive for the implicit "
                       "scheme.");

    fe_collection.push_back(FESystem<dim>(FE_Q<dim>(1), dim));
    fe_collection.push_back(FESystem<dim>(FE_Nothing<dim>(), dim));
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::setup_system()
  {
    if (cloud)
      {
        setup_cloud_system();
        return;
      }
    // Unknowns only on cells that hold points.
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        cell->set_active_fe_index(
          points.handler().n_particles_in_cell(cell) > 0 ? 0 : 1);
    dof_handler.distribute_dofs(fe_collection);
    owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);

    // Contact nodes stay engaged into the new step only while material
    // still touches them.
    if (dirichlet.has_contact())
      {
        const TrilinosWrappers::MPI::Vector touching = contact_gaps(false);
        for_each_contact_node(
          [&](const unsigned int node, const types::global_dof_index dof0,
              const auto &) {
            if (touching(dof0) == 0.)
              engaged_contact_nodes.erase(node);
          });
      }
    make_constraints();

    const MPI_Comm         comm = points.get_communicator();
    DynamicSparsityPattern dsp(relevant_dofs);
    // Constrained rows keep their entries, so that releasing a contact node
    // needs no new pattern.
    DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, true);
    SparsityTools::distribute_sparsity_pattern(dsp, owned_dofs, comm,
                                               relevant_dofs);
    reinit_linear_system(dsp);
    build_cell_groups();
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::reinit_linear_system(DynamicSparsityPattern &dsp)
  {
    const MPI_Comm comm = points.get_communicator();
    factorization.reset();
    tangent.reinit(owned_dofs, owned_dofs, dsp, comm);
    residual.reinit(owned_dofs, comm);
    correction.reinit(owned_dofs, comm);
    displacement.reinit(owned_dofs, comm);
    displacement_ghosted.reinit(owned_dofs, relevant_dofs, comm);
    velocity_ghosted.reinit(owned_dofs, relevant_dofs, comm);
    acceleration_ghosted.reinit(owned_dofs, relevant_dofs, comm);
    if (dirichlet.has_contact())
      unconstrained_residual.reinit(owned_dofs, relevant_dofs, comm, true);
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::build_cell_groups()
  {
    unsigned int n_groups = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned() || cell->active_fe_index() != 0)
          continue;
        PointGroup &group = next_group(n_groups);
        group.dofs.resize(fe_collection[0].n_dofs_per_cell());
        cell->get_dof_indices(group.dofs);
        group.weight = quadrature_scale(cell);
        group.supports.resize(points.handler().n_particles_in_cell(cell));
        unsigned int q = 0;
        for (auto particle = points.handler().particles_in_cell(cell).begin();
             particle != points.handler().particles_in_cell(cell).end();
             ++particle, ++q)
          {
            group.particles.push_back(particle);
            basis.evaluate(cell->active_cell_index(),
                           particle->get_reference_location(),
                           group.supports[q]);
          }
      }
    groups.resize(n_groups);
  }



  template <int dim>
  typename ImplicitIntegrator<dim>::PointGroup &
  ImplicitIntegrator<dim>::next_group(unsigned int &n_groups)
  {
    // Groups are reused from step to step, so that their vectors keep
    // their memory.
    if (n_groups == groups.size())
      groups.emplace_back();
    PointGroup &group = groups[n_groups++];
    group.particles.clear();
    group.weight = 1.;
    return group;
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::setup_cloud_system()
  {
    {
      TimerOutput::Scope t(timer, "meshfree shape functions");
      meshfree->reinit(cloud->positions);
      unsigned int n_groups = 0;
      for (auto particle = points.handler().begin();
           particle != points.handler().end();
           ++particle)
        {
          PointGroup &group = next_group(n_groups);
          group.particles.push_back(particle);
          group.supports.resize(1);
          Support<dim> &support = group.supports[0];
          try
            {
              meshfree->evaluate(particle->get_location(), support);
            }
          catch (const RunError &e)
            {
              throw RunError("Material point " +
                               std::to_string(particle->get_id()) + ": " +
                               e.what(),
                             false);
            }
          group.dofs.resize(support.n_nodes * dim);
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            for (unsigned int a = 0; a < dim; ++a)
              group.dofs[i * dim + a] = support.nodes[i] * dim + a;
        }
      groups.resize(n_groups);
    }
    // MLS shape functions can be negative: a lumped nodal mass must still
    // be positive.
    if (dynamic && lumped_mass &&
        meshfree->kind() == MeshfreeBasis<dim>::Kind::mls)
      {
        std::vector<double> nodal_mass(cloud->size(), 0.);
        for (const PointGroup &group : groups)
          for (unsigned int k = 0; k < group.supports[0].n_nodes; ++k)
            nodal_mass[group.supports[0].nodes[k]] +=
              group.supports[0].N[k] *
              group.particles[0]->get_properties()[PointLayout<dim>::mass];
        for (unsigned int i = 0; i < cloud->size(); ++i)
          if (nodal_mass[i] < 0.)
            throw RunError("Node " + std::to_string(i) + " at (" +
                             Utilities::to_string(cloud->positions[i][0]) +
                             ", ...) has a negative lumped MLS mass; use "
                             "Newmark/Mass matrix = consistent, or "
                             "Method = GMM-LME.",
                           false);
      }
    // One rank holds the whole cloud (the simulator refuses more).
    owned_dofs    = complete_index_set(cloud->size() * dim);
    relevant_dofs = owned_dofs;
    make_cloud_constraints();
    DynamicSparsityPattern dsp = cloud_sparsity_pattern();
    reinit_linear_system(dsp);
  }



  template <int dim>
  DynamicSparsityPattern
  ImplicitIntegrator<dim>::cloud_sparsity_pattern() const
  {
    DynamicSparsityPattern dsp(relevant_dofs);
    for (const PointGroup &group : groups)
      constraints.add_entries_local_to_global(group.dofs, dsp, true);
    for (const unsigned int node : unreached_nodes)
      for (unsigned int a = 0; a < dim; ++a)
        dsp.add(node * dim + a, node * dim + a);
    return dsp;
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::make_cloud_constraints()
  {
    constraints.clear();
    constraints.reinit(relevant_dofs);
    const unsigned int n_nodes = cloud->size();
    std::vector<std::array<bool, dim>> held(n_nodes);
    for (unsigned int i = 0; i < n_nodes; ++i)
      held[i] = cloud->held_components(i);
    // A node that no point reaches has no stiffness and no mass: it stays
    // where it is, which keeps the matrix regular.
    std::vector<bool> reached(n_nodes, false);
    for (const PointGroup &group : groups)
      for (unsigned int k = 0; k < group.supports[0].n_nodes; ++k)
        reached[group.supports[0].nodes[k]] = true;
    unreached_nodes.clear();
    for (unsigned int i = 0; i < n_nodes; ++i)
      if (!reached[i])
        {
          for (unsigned int a = 0; a < dim; ++a)
            constraints.add_line(i * dim + a);
          held[i].fill(false);
          unreached_nodes.push_back(i);
        }

    if (meshfree->kind() == MeshfreeBasis<dim>::Kind::lme)
      {
        for (unsigned int i = 0; i < n_nodes; ++i)
          for (unsigned int a = 0; a < dim; ++a)
            if (held[i][a])
              constraints.add_line(i * dim + a);
        constraints.close();
        return;
      }

    // MLS, per component a: sum_j N_j(x_d) u_j = 0 at each held node d.
    // With D the held nodes and F the others, A_DD u_D = -A_DF u_F, so
    // u_D = C u_F with C = -A_DD^-1 A_DF, a dense solve of the size of D.
    // The shape functions at every node that holds a component.
    std::map<unsigned int, Support<dim>> support_at;
    for (unsigned int i = 0; i < n_nodes; ++i)
      if (std::find(held[i].begin(), held[i].end(), true) != held[i].end())
        try
          {
            meshfree->evaluate(cloud->positions[i], support_at[i]);
          }
        catch (const RunError &e)
          {
            throw RunError("The MLS wall condition at node " +
                             std::to_string(i) + ": " + e.what(),
                           false);
          }
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
            constraints.add_line(row);
            for (unsigned int c = 0; c < free_nodes.size(); ++c)
              if (std::abs(C(r, c)) > cut)
                constraints.add_entry(row, free_nodes[c] * dim + a, C(r, c));
          }
      }
    constraints.close();
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::move_cloud()
  {
    for (unsigned int i = 0; i < cloud->size(); ++i)
      {
        const std::array<bool, dim> held = cloud->held_components(i);
        Tensor<1, dim>              du, v, a;
        for (unsigned int d = 0; d < dim; ++d)
          {
            du[d] = displacement_ghosted(i * dim + d);
            v[d]  = velocity_ghosted(i * dim + d);
            a[d]  = acceleration_ghosted(i * dim + d);
          }
        // MLS nodal values are not displacements at the node; a held node
        // stays on its wall.
        for (unsigned int d = 0; d < dim; ++d)
          if (!held[d])
            cloud->positions[i][d] += du[d];
        if (dynamic)
          {
            const Tensor<1, dim> a_new = end_acceleration(du, v, a);
            cloud->velocities[i] = v + velocity_increment(a, a_new);
            cloud->accelerations[i] = a_new;
          }
      }
    cloud->has_history = true;
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::make_constraints()
  {
    // Grid conditions on the nodes of active cells: a wall along an axis
    // fixes that component; a slanted wall ties the components so that the
    // normal displacement vanishes.
    constraints.clear();
    constraints.reinit(relevant_dofs);
    bool unsupported_corner = false;
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    for_each_constrained_vertex([&](const auto &        cell,
                                    const unsigned int  v,
                                    const unsigned int  node,
                                    const auto &        constraint) {
      std::array<types::global_dof_index, dim> dofs;
      for (unsigned int a = 0; a < dim; ++a)
        dofs[a] = cell->vertex_dof_index(v, a, 0);
      // A free contact node keeps no slip along the wall, which a body
      // rolling without slip satisfies on the whole line of the wall; only
      // its normal motion is free.
      const bool free_contact =
        constraint.unilateral && engaged_contact_nodes.count(node) == 0;
      if (free_contact || constraint.n_normals == dim)
        {
          for (unsigned int a = 0; a < dim; ++a)
            if ((!free_contact || std::abs(constraint.outward[a]) < 0.5) &&
                !constraints.is_constrained(dofs[a]))
              constraints.add_line(dofs[a]);
          return;
        }
      for (unsigned int k = 0; k < constraint.n_normals; ++k)
        {
          const Tensor<1, dim> &n     = constraint.normals[k];
          unsigned int          pivot = 0;
          for (unsigned int a = 1; a < dim; ++a)
            if (std::abs(n[a]) > std::abs(n[pivot]))
              pivot = a;
          if (constraints.is_constrained(dofs[pivot]))
            continue;
          const bool along_axis = std::abs(std::abs(n[pivot]) - 1.) < 1e-12;
          if (!along_axis && constraint.n_normals > 1)
            {
              unsupported_corner = true;
              continue;
            }
          constraints.add_line(dofs[pivot]);
          if (!along_axis)
            for (unsigned int a = 0; a < dim; ++a)
              if (a != pivot)
                constraints.add_entry(dofs[pivot], dofs[a], -n[a] / n[pivot]);
        }
    });
    // Decided on all ranks together, so that all stop.
    if (Utilities::MPI::logical_or(unsupported_corner,
                                   points.get_communicator()))
      throw RunError("Boundary conditions: the implicit schemes support "
                     "corners between slip walls only when the walls are "
                     "aligned with the axes, and material reached such a "
                     "corner.");
    constraints.close();

  }



  template <int dim>
  template <typename Function>
  void
  ImplicitIntegrator<dim>::for_each_constrained_vertex(const Function &f) const
  {
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned() || cell->active_fe_index() != 0)
          continue;
        for (const unsigned int v : cell->vertex_indices())
          {
            const unsigned int node =
              grid.node_of(cell->active_cell_index(), v);
            if (const auto *constraint = dirichlet.constraint_of(node))
              f(cell, v, node, *constraint);
          }
      }
  }



  template <int dim>
  template <typename Function>
  void
  ImplicitIntegrator<dim>::for_each_contact_node(const Function &f) const
  {
    std::set<unsigned int> visited;
    for_each_constrained_vertex([&](const auto &        cell,
                                    const unsigned int  v,
                                    const unsigned int  node,
                                    const auto &        constraint) {
      if (constraint.unilateral && visited.insert(node).second)
        f(node, cell->vertex_dof_index(v, 0, 0), constraint);
    });
  }



  template <int dim>
  TrilinosWrappers::MPI::Vector
  ImplicitIntegrator<dim>::contact_gaps(const bool after_solve) const
  {
    using Layout         = PointLayout<dim>;
    const MPI_Comm comm  = points.get_communicator();
    // Summed over the ranks that share a node, so that all decide alike.
    TrilinosWrappers::MPI::Vector flags;
    flags.reinit(owned_dofs, relevant_dofs, comm, true);
    std::vector<types::global_dof_index> dofs(
      fe_collection[0].n_dofs_per_cell());
    Support<dim> support;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned() || cell->active_fe_index() != 0)
          continue;
        std::vector<
          std::pair<unsigned int,
                    const typename DirichletConditions<dim>::Constraint *>>
          contact_vertices;
        for (const unsigned int v : cell->vertex_indices())
          {
            const auto *c = dirichlet.constraint_of(
              grid.node_of(cell->active_cell_index(), v));
            if (c != nullptr && c->unilateral)
              contact_vertices.emplace_back(v, c);
          }
        if (contact_vertices.empty())
          continue;
        cell->get_dof_indices(dofs);
        for (const auto &particle : points.handler().particles_in_cell(cell))
          {
            const ArrayView<const double> p = particle.get_properties();
            const double reach = reach_of(p);
            Point<dim> x = particle.get_location();
            if (after_solve)
              {
                basis.evaluate(cell->active_cell_index(),
                               particle.get_reference_location(),
                               support);
                for (unsigned int i = 0; i < support.n_nodes; ++i)
                  for (unsigned int a = 0; a < dim; ++a)
                    x[a] += support.N[i] * displacement_ghosted(dofs[i * dim + a]);
              }
            for (const auto &[v, c] : contact_vertices)
              {
                const double gap_before =
                  (cell->vertex(v) - particle.get_location()) * c->outward;
                const double gap = (cell->vertex(v) - x) * c->outward;
                if (gap < reach && (!after_solve || gap < gap_before))
                  flags(cell->vertex_dof_index(v, 0, 0)) += 1.;
              }
          }
      }
    flags.compress(VectorOperation::add);
    TrilinosWrappers::MPI::Vector ghosted(owned_dofs, relevant_dofs, comm);
    ghosted = flags;
    return ghosted;
  }



  template <int dim>
  bool
  ImplicitIntegrator<dim>::update_contact_set()
  {
    const MPI_Comm                comm = points.get_communicator();
    // The out-of-balance force before constraints, kept for contact walls.
    TrilinosWrappers::MPI::Vector residual_at_nodes(owned_dofs,
                                                    relevant_dofs,
                                                    comm);
    if (dirichlet.has_contact())
      residual_at_nodes = unconstrained_residual;
    unsigned int released = 0, engaged = 0;
    if (cloud)
      {
        // A node held by a contact wall lets go when the wall pulls. As on
        // the grid, a point that the step brings within half its spacing
        // of a wall, moving towards it, engages the nodes next to it
        // (within one nodal spacing) that lie within that distance of the
        // wall or beyond it.
        // The cloud's outer nodes reach a wall before the material does,
        // so the nodes alone cannot tell; and a held node far from the
        // material would be a pivot that levers the body off the wall.
        // The cloud lives on one rank.
        // A node may be held by several walls (at a corner); each
        // (node, wall) pair changes at most once per step.
        const unsigned int n_walls = cloud->walls.size();
        for (unsigned int i = 0; i < cloud->size(); ++i)
          for (unsigned int w = 0; w < n_walls; ++w)
            {
              if (!cloud->is_held_by(i, w) ||
                  changed_contact_nodes.count(i * n_walls + w) > 0 ||
                  cloud->walls[w].kind !=
                    DirichletConditions<dim>::WallKind::contact)
                continue;
              double pull = 0.;
              for (unsigned int a = 0; a < dim; ++a)
                pull -= residual_at_nodes(i * dim + a) *
                        cloud->walls[w].outward[a];
              if (pull > 0.)
                {
                  cloud->engaged_walls[i] &= ~(1u << w);
                  changed_contact_nodes.insert(i * n_walls + w);
                  ++released;
                }
            }
        for (const PointGroup &group : groups)
          {
            const Support<dim> &support = group.supports[0];
            const double reach = reach_of(group.particles[0]->get_properties());
            const Point<dim> x_old = group.particles[0]->get_location();
            Point<dim>       x_new = x_old;
            for (unsigned int k = 0; k < support.n_nodes; ++k)
              for (unsigned int a = 0; a < dim; ++a)
                x_new[a] += support.N[k] * displacement_ghosted(group.dofs[k * dim + a]);
            for (unsigned int w = 0; w < cloud->walls.size(); ++w)
              {
                const auto & c       = cloud->walls[w];
                const double gap_new = c.offset - c.outward * x_new;
                if (!(gap_new < reach && gap_new < c.offset - c.outward * x_old))
                  continue;
                for (unsigned int k = 0; k < support.n_nodes; ++k)
                  {
                    const unsigned int node = support.nodes[k];
                    const Point<dim> &x_node = cloud->positions[node];
                    if (!cloud->is_held_by(node, w) &&
                        changed_contact_nodes.count(node * n_walls + w) == 0 &&
                        c.offset - c.outward * x_node < reach &&
                        x_node.distance(x_new) < cloud->spacing())
                      {
                        cloud->engaged_walls[node] |= 1u << w;
                        changed_contact_nodes.insert(node * n_walls + w);
                        ++engaged;
                      }
                  }
              }
          }
        if (released + engaged > 0)
          pcout << "    walls: " << released << " node(s) released, "
                << engaged << " held" << std::endl;
        return released + engaged > 0;
      }

    const TrilinosWrappers::MPI::Vector closing = contact_gaps(true);
    // Ranks that share a node see the same ghosted values and so decide
    // alike; each node is counted by the owner of its first dof.
    for_each_contact_node([&](const unsigned int            node,
                              const types::global_dof_index dof0,
                              const auto &                  constraint) {
      if (changed_contact_nodes.count(node) > 0)
        return;
      const bool counted = owned_dofs.is_element(dof0);
      if (engaged_contact_nodes.count(node) > 0)
        {
          // The wall force on the material is minus the out-of-balance
          // force; it pulls when it points out of the grid.
          double pull = 0.;
          for (unsigned int a = 0; a < dim; ++a)
            pull -= residual_at_nodes(dof0 + a) * constraint.outward[a];
          if (pull > 0.)
            {
              engaged_contact_nodes.erase(node);
              changed_contact_nodes.insert(node);
              released += counted;
            }
        }
      else if (closing(dof0) > 0.)
        {
          engaged_contact_nodes.insert(node);
          changed_contact_nodes.insert(node);
          engaged += counted;
        }
    });
    released = Utilities::MPI::sum(released, comm);
    engaged  = Utilities::MPI::sum(engaged, comm);
    if (released + engaged > 0)
      pcout << "    contact: " << released << " node(s) released, " << engaged
            << " engaged" << std::endl;
    return released + engaged > 0;
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::constrain_initial_conditions()
  {
    TrilinosWrappers::MPI::Vector velocity(projected_velocity),
      acceleration(projected_acceleration);
    // Grid conditions hold for the nodal velocity and acceleration too.
    constraints.distribute(velocity);
    constraints.distribute(acceleration);
    velocity_ghosted     = velocity;
    acceleration_ghosted = acceleration;
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::project_initial_conditions()
  {
    using Layout      = PointLayout<dim>;
    const MPI_Comm comm = points.get_communicator();
    projected_velocity.reinit(owned_dofs, comm);
    projected_acceleration.reinit(owned_dofs, comm);
    if (cloud && cloud->has_history)
      {
        // GMM nodes carry their own velocity and acceleration ([I]
        // Algorithm 2); only the first step takes them from the points.
        for (unsigned int i = 0; i < cloud->size(); ++i)
          for (unsigned int a = 0; a < dim; ++a)
            {
              projected_velocity(i * dim + a)     = cloud->velocities[i][a];
              projected_acceleration(i * dim + a) = cloud->accelerations[i][a];
            }
        projected_velocity.compress(VectorOperation::insert);
        projected_acceleration.compress(VectorOperation::insert);
        constrain_initial_conditions();
        return;
      }
    // Writable ghost entries, summed into their owners by compress().
    TrilinosWrappers::MPI::Vector mass, momentum, mass_acceleration;
    mass.reinit(owned_dofs, relevant_dofs, comm, true);
    momentum.reinit(owned_dofs, relevant_dofs, comm, true);
    mass_acceleration.reinit(owned_dofs, relevant_dofs, comm, true);

    for (const PointGroup &group : groups)
      for (unsigned int q = 0; q < group.particles.size(); ++q)
        {
          const Support<dim> &          support = group.supports[q];
          const ArrayView<const double> p = group.particles[q]->get_properties();
          for (unsigned int i = 0; i < support.n_nodes; ++i)
            for (unsigned int a = 0; a < dim; ++a)
              {
                const types::global_dof_index dof = group.dofs[i * dim + a];
                const double Nm = support.N[i] * p[Layout::mass];
                mass(dof) += Nm;
                momentum(dof) += Nm * p[Layout::velocity + a];
                mass_acceleration(dof) += Nm * p[points.acceleration_index() + a];
              }
        }
    mass.compress(VectorOperation::add);
    momentum.compress(VectorOperation::add);
    mass_acceleration.compress(VectorOperation::add);

    for (const auto i : owned_dofs)
      if (mass(i) > 0.)
        {
          projected_velocity(i)     = momentum(i) / mass(i);
          projected_acceleration(i) = mass_acceleration(i) / mass(i);
        }
    projected_velocity.compress(VectorOperation::insert);
    projected_acceleration.compress(VectorOperation::insert);
    constrain_initial_conditions();
  }
} // namespace mpm

namespace mpm
{
  template <int dim>
  void
  ImplicitIntegrator<dim>::assemble(const double load_factor,
                                       const bool   with_tangent)
  {
    using Layout = PointLayout<dim>;
    residual     = 0.;
    correction   = 0.; // holds f_ext here, for the convergence measure
    if (dirichlet.has_contact())
      unconstrained_residual = 0.;
    if (with_tangent)
      {
        tangent = 0.;
        factorization.reset();
      }
    double internal_force_square = 0.;
    double momentum_rate_square  = 0.;
    bool   inverted              = false;

    FullMatrix<double>          cell_tangent;
    Vector<double>              cell_residual, cell_external;
    Vector<double>              point_force;
    FullMatrix<double>          point_tangent;
    std::vector<Tensor<1, dim>> du, v_n, a_n, a_node;
    std::vector<double>         internal;
    const double                mass_stiffness =
      dynamic ? (1. - bossak_alpha) / (beta * time_step * time_step) : 0.;

    for (const PointGroup &group : groups)
      {
        const std::vector<types::global_dof_index> &dofs = group.dofs;
        const unsigned int dofs_per_cell = dofs.size();
        // A group of one point (every meshfree point) writes its tangent
        // straight into the group's matrix.
        const bool          single_point = group.particles.size() == 1;
        FullMatrix<double> &own_tangent =
          single_point ? cell_tangent : point_tangent;
        if (!single_point)
          cell_tangent.reinit(dofs_per_cell, dofs_per_cell);
        cell_residual.reinit(dofs_per_cell);
        cell_external.reinit(dofs_per_cell);
        const double weight = group.weight;
        gather(group, du, v_n, a_n);

        for (unsigned int q = 0; q < group.particles.size(); ++q)
          {
            const Support<dim> &          support = group.supports[q];
            const ArrayView<const double> p =
              group.particles[q]->get_properties();
            const Tensor<2, dim>          dF =
              PointAssembly<dim>::deformation_increment(support, du);
            const Tensor<2, dim> F_n = Layout::get_deformation_gradient(p);
            const StepKinematics k   = step_kinematics(dF, F_n);
            const Material &material =
              *materials[static_cast<unsigned int>(p[Layout::material_id])];
            const SymmetricTensor<2, 3> old_stress = Layout::get_stress(p);
            const ArrayView<const double> old_internal(
              &p[Layout::internal_variables], material.n_internal_variables());
            SymmetricTensor<2, 3> stress = old_stress;
            internal.assign(old_internal.begin(), old_internal.end());
            if (!(determinant(k.F_new) > 0.))
              inverted = true;
            else
              material.update_stress(k,
                                     stress,
                                     ArrayView<double>(internal.data(),
                                                       internal.size()));
            SymmetricTensor<4, 3> c;
            if (with_tangent && !inverted)
              c = material.spatial_tangent(k, old_stress, old_internal);
            PointAssembly<dim>::internal_force(
              support,
              dF,
              weight * determinant(dF * F_n) * p[Layout::reference_volume],
              stress,
              &c,
              point_force,
              with_tangent ? &own_tangent : nullptr);

            for (unsigned int i = 0; i < support.n_nodes; ++i)
              for (unsigned int a = 0; a < dim; ++a)
                {
                  const double external =
                    load_factor * support.N[i] *
                    (p[points.point_load_index() + a] +
                     p[Layout::mass] * gravity[a]);
                  cell_external(i * dim + a) += external;
                  cell_residual(i * dim + a) +=
                    external - point_force(i * dim + a);
                }
            if (with_tangent && !single_point)
              cell_tangent.add(1., point_tangent);

            if (dynamic)
              {
                // Inertia with the Newmark (Bossak) nodal acceleration, and
                // its derivative. Consistent: m_p a(x_p) at the point, mass
                // m_p N_i N_k ([I] eq. 30). Lumped: m_p N_i a_i, mass
                // m_p N_i on the diagonal.
                a_node.resize(support.n_nodes);
                Tensor<1, dim> a_point;
                for (unsigned int k = 0; k < support.n_nodes; ++k)
                  {
                    a_node[k] = (1. - bossak_alpha) *
                                  end_acceleration(du[k], v_n[k], a_n[k]) +
                                bossak_alpha * a_n[k];
                    a_point += support.N[k] * a_node[k];
                  }
                const double m = p[Layout::mass];
                momentum_rate_square +=
                  m * m * Layout::get_velocity(p).norm_square() /
                  (time_step * time_step);
                for (unsigned int i = 0; i < support.n_nodes; ++i)
                  {
                    const double mass_i = support.N[i] * m;
                    for (unsigned int a = 0; a < dim; ++a)
                      cell_residual(i * dim + a) -=
                        mass_i * (lumped_mass ? a_node[i][a] : a_point[a]);
                    if (!with_tangent)
                      continue;
                    for (unsigned int k = 0; k < support.n_nodes; ++k)
                      if (!lumped_mass || k == i)
                        for (unsigned int a = 0; a < dim; ++a)
                          cell_tangent(i * dim + a, k * dim + a) +=
                            mass_i * (lumped_mass ? 1. : support.N[k]) *
                            mass_stiffness;
                  }
              }
          }

        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          if (!constraints.is_constrained(dofs[i]))
            internal_force_square +=
              (cell_external(i) - cell_residual(i)) *
              (cell_external(i) - cell_residual(i));
        if (with_tangent && !add_to_tangent(dofs, cell_tangent))
          constraints.distribute_local_to_global(
            cell_tangent, cell_residual, dofs, tangent, residual);
        else
          constraints.distribute_local_to_global(cell_residual, dofs, residual);
        constraints.distribute_local_to_global(cell_external, dofs, correction);
        if (dirichlet.has_contact())
          unconstrained_residual.add(dofs, cell_residual);
      }
    // A node that no point reaches has an empty row: a unit diagonal
    // keeps the matrix regular (its dofs are held at zero).
    if (with_tangent)
      for (const unsigned int node : unreached_nodes)
        for (unsigned int a = 0; a < dim; ++a)
          tangent.add(node * dim + a, node * dim + a, 1.);
    // Compress before a throw: entries buffered for other ranks would
    // otherwise survive `= 0.` and join the next assembly (a line search
    // goes on after a failed trial).
    if (with_tangent)
      tangent.compress(VectorOperation::add);
    residual.compress(VectorOperation::add);
    correction.compress(VectorOperation::add);
    if (dirichlet.has_contact())
      unconstrained_residual.compress(VectorOperation::add);
    if (Utilities::MPI::logical_or(inverted, points.get_communicator()))
      throw RunError("A Newton iterate inverted a material point (det F <= "
                     "0).");

    // The scale of the forces ([B] eq. 31): the external load, or, where
    // none acts (a scene driven by its boundaries or its initial motion),
    // the internal forces cell by cell, and in dynamic runs the momentum
    // rate m v_n / dt, whichever is larger. A residual r changes the step's
    // velocities by the order of r dt / m, so against m v_n / dt the ratio
    // is of the order of the relative velocity error; without it a body in
    // free flight would compare round-off with round-off and never converge.
    external_force_norm = correction.l2_norm();
    if (!(external_force_norm > 0.))
      {
        Tensor<1, 2> squares;
        squares[0] = internal_force_square;
        squares[1] = momentum_rate_square;
        squares    = Utilities::MPI::sum(squares, points.get_communicator());
        external_force_norm = std::sqrt(std::max(squares[0], squares[1]));
      }
  }



  template <int dim>
  double
  ImplicitIntegrator<dim>::quadrature_scale(
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
    for (const auto &particle : points.handler().particles_in_cell(cell))
      {
        const ArrayView<const double> p = particle.get_properties();
        volume += determinant(Layout::get_deformation_gradient(p)) *
                  p[Layout::reference_volume];
      }
    return cell->measure() / volume;
  }



  template <int dim>
  bool
  ImplicitIntegrator<dim>::add_to_tangent(
    const std::vector<types::global_dof_index> &dofs,
    const FullMatrix<double> &                  matrix)
  {
    for (const types::global_dof_index dof : dofs)
      if (!owned_dofs.is_element(dof) || constraints.is_constrained(dof))
        return false;
    // deal.II gives only const access to the Epetra matrix; its values
    // belong to `tangent`, which is not const. FillComplete sorts each
    // row's local column indices, so a group's columns sorted the same way
    // are found in one pass along each row (a column not found throws).
    Epetra_CrsMatrix &epetra =
      const_cast<Epetra_CrsMatrix &>(tangent.trilinos_matrix());
    if (!epetra.Filled())
      return false;
    const unsigned int n = dofs.size();
    tangent_columns.resize(n);
    for (unsigned int k = 0; k < n; ++k)
      tangent_columns[k] = {epetra.ColMap().LID(
                              static_cast<TrilinosWrappers::types::int_type>(
                                dofs[k])),
                            k};
    std::sort(tangent_columns.begin(), tangent_columns.end());
    tangent_offsets.resize(n);
    const int *previous_columns = nullptr;
    int        previous_length  = -1;
    for (unsigned int i = 0; i < n; ++i)
      {
        int     length;
        double *values;
        int *   columns;
        AssertThrow(epetra.ExtractMyRowView(
                      epetra.RowMap().LID(
                        static_cast<TrilinosWrappers::types::int_type>(
                          dofs[i])),
                      length,
                      values,
                      columns) == 0,
                    ExcMessage("An owned row of the tangent is missing."));
        // The rows of one node's components usually hold the same columns:
        // then the offsets found for the first serve them all.
        if (length != previous_length ||
            !std::equal(columns, columns + length, previous_columns))
          {
            int position = 0;
            for (const auto &[column, k] : tangent_columns)
              {
                while (position < length && columns[position] < column)
                  ++position;
                AssertThrow(position < length && columns[position] == column,
                            ExcMessage("A group's dofs are missing from the "
                                       "sparsity pattern of the tangent."));
                tangent_offsets[k] = position;
              }
            previous_columns = columns;
            previous_length  = length;
          }
        for (unsigned int k = 0; k < n; ++k)
          values[tangent_offsets[k]] += matrix(i, k);
      }
    return true;
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::report_tangent_error(const double load_factor)
  {
    // splitmix64 of the global dof index, in [-1, 1): a fixed direction
    // for a given numbering of the dofs.
    auto pseudo_random = [](std::uint64_t z) {
      z += 0x9E3779B97F4A7C15ull;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      z ^= z >> 31;
      return 2. * static_cast<double>(z >> 11) * 0x1.0p-53 - 1.;
    };
    // What assemble() overwrites, put back as it was afterwards.
    const TrilinosWrappers::MPI::Vector start(displacement);
    const TrilinosWrappers::MPI::Vector start_residual(residual);
    const TrilinosWrappers::MPI::Vector external_force(correction);
    TrilinosWrappers::MPI::Vector       start_unconstrained_residual;
    if (dirichlet.has_contact())
      start_unconstrained_residual = unconstrained_residual;
    const double start_external_force_norm = external_force_norm;

    const double probe_size = 3e-9 * grid.minimum_cell_size();
    TrilinosWrappers::MPI::Vector direction(displacement);
    for (const types::global_dof_index i : owned_dofs)
      direction[i] = probe_size * pseudo_random(i);
    direction.compress(VectorOperation::insert);
    // distribute() of u + d keeps the constraints' inhomogeneities, which
    // u satisfies, so the step taken is d within the constraints.
    TrilinosWrappers::MPI::Vector perturbed(start);
    perturbed += direction;
    constraints.distribute(perturbed);
    direction = perturbed;
    direction -= start;
    TrilinosWrappers::MPI::Vector tangent_times_direction(direction);
    tangent.vmult(tangent_times_direction, direction);

    auto assemble_at = [&](const TrilinosWrappers::MPI::Vector &u) {
      displacement         = u;
      displacement_ghosted = u;
      assemble(load_factor, false);
    };
    TrilinosWrappers::MPI::Vector mismatch;
    bool                          inverted = false;
    try
      {
        assemble_at(perturbed);
        mismatch  = residual;
        perturbed = start;
        perturbed -= direction;
        assemble_at(perturbed);
        mismatch -= residual;
      }
    catch (const RunError &)
      {
        inverted = true;
      }
    displacement           = start;
    displacement_ghosted   = start;
    residual               = start_residual;
    correction             = external_force;
    if (dirichlet.has_contact())
      unconstrained_residual = start_unconstrained_residual;
    external_force_norm    = start_external_force_norm;
    if (inverted)
      {
        pcout << "    tangent check: not made, u + d or u - d inverts a "
                 "point"
              << std::endl;
        return;
      }

    // r = f_ext - f_int - inertia and K = -dr/du.
    mismatch *= 0.5;
    mismatch += tangent_times_direction;
    for (const types::global_dof_index i : owned_dofs)
      if (constraints.is_constrained(i))
        {
          mismatch[i]                = 0.;
          tangent_times_direction[i] = 0.;
        }
    mismatch.compress(VectorOperation::insert);
    tangent_times_direction.compress(VectorOperation::insert);

    std::ostringstream error_text;
    error_text << std::scientific << std::setprecision(3)
               << mismatch.l2_norm() / tangent_times_direction.l2_norm();
    pcout << "    tangent check: |K d + (r(u + d) - r(u - d)) / 2| / |K d| = "
          << error_text.str() << std::endl;
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::solve_linear_system()
  {
    correction = 0.;
    try
      {
        if (linear_solver != "CG-AMG")
          {
            if (!factorization)
              {
                factorization =
                  std::make_unique<TrilinosWrappers::SolverDirect>(
                    direct_solver_control,
                    TrilinosWrappers::SolverDirect::AdditionalData(
                      false,
                      linear_solver == "MUMPS" ? "Amesos_Mumps" :
                                                 "Amesos_Klu"));
                factorization->initialize(tangent);
              }
            factorization->solve(correction, residual);
          }
        else
          {
            SolverControl control(1000,
                                  1e-10 * residual.l2_norm(),
                                  false,
                                  false);
            TrilinosWrappers::PreconditionAMG                 amg;
            TrilinosWrappers::PreconditionAMG::AdditionalData data;
            data.elliptic              = true;
            data.higher_order_elements = false;
            amg.initialize(tangent, data);
            SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
            cg.solve(tangent, correction, residual, amg);
          }
      }
    catch (const std::exception &e)
      {
        // A singular tangent or a solver that does not converge: the
        // residual norms are global, so every rank gets here together.
        throw RunError(std::string("The linear solver failed: ") + e.what());
      }
    constraints.distribute(correction);
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::step(const double load_factor, const double dt)
  {
    // A failed step is retried with half the size from the same state, so
    // the walls' active set must not keep what the failed attempt did.
    const std::set<unsigned int> engaged_before = engaged_contact_nodes;
    const std::vector<unsigned int> cloud_engaged_before =
      cloud ? cloud->engaged_walls : std::vector<unsigned int>();
    try
      {
        solve_step(load_factor, dt);
      }
    catch (...)
      {
        engaged_contact_nodes = engaged_before;
        if (cloud)
          cloud->engaged_walls = cloud_engaged_before;
        throw;
      }
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::solve_step(const double load_factor,
                                      const double dt)
  {
    time_step = dt;
    {
      TimerOutput::Scope t(timer, "setup system");
      setup_system();
      if (dynamic)
        project_initial_conditions();
    }
    // Dynamic runs start Newton from the constant-acceleration predictor
    // du = dt v_n + dt^2/2 a_n: for a body in motion, du = 0 would mean an
    // inertia force of order m v_n / dt at the first iterate.
    displacement = 0.;
    if (dynamic)
      {
        displacement.add(dt, projected_velocity);
        displacement.add(0.5 * dt * dt, projected_acceleration);
        constraints.distribute(displacement);
      }
    displacement_ghosted = displacement;

    // Contact boundaries: solve, correct the contact set, and solve again
    // from there until the set holds. A node changes at most once per step:
    // a node that pulls while held but moves into the wall when free would
    // otherwise flip for ever.
    changed_contact_nodes.clear();
    constexpr unsigned int max_contact_rounds = 10;
    for (unsigned int round = 1;; ++round)
      {
        solve_newton(load_factor);
        const bool active_set =
          dirichlet.has_contact() || (cloud && !cloud->walls.empty());
        if (!active_set || !update_contact_set())
          break;
        if (round == max_contact_rounds)
          throw RunError("The contact nodes did not settle in " +
                         std::to_string(max_contact_rounds) +
                         " rounds of the step.");
        if (cloud)
          {
            // MLS ties newly held nodes to their neighbours: new entries.
            make_cloud_constraints();
            factorization.reset();
            tangent.reinit(owned_dofs,
                           owned_dofs,
                           cloud_sparsity_pattern(),
                           points.get_communicator());
          }
        else
          make_constraints();
        constraints.distribute(displacement);
        displacement_ghosted = displacement;
        if (dynamic)
          constrain_initial_conditions();
      }
    TimerOutput::Scope t(timer, "G2P");
    update_points();
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::solve_newton(const double load_factor)
  {
    bool converged = false;
    bool assembled = false; // the line search assembled at this iterate
    for (unsigned int iteration = 0; iteration <= max_iterations; ++iteration)
      {
        // Modified Newton keeps the first iteration's tangent.
        const bool new_tangent = iteration == 0 || !modified_newton;
        if (!assembled)
          {
            TimerOutput::Scope t(timer, "assemble");
            assemble(load_factor, new_tangent);
          }
        const double ratio =
          external_force_norm > 0. ? residual.l2_norm() / external_force_norm :
                                     0.;
        // Formatted apart, so that the screen's precision stays as it is.
        std::ostringstream ratio_text;
        ratio_text << std::scientific << std::setprecision(3) << ratio;
        pcout << "    Newton " << std::setw(2) << iteration
              << ": out-of-balance ratio " << ratio_text.str() << std::endl;
        if (!std::isfinite(ratio))
          throw RunError("The out-of-balance force is not finite.");
        if (check_tangent && new_tangent)
          {
            TimerOutput::Scope t(timer, "tangent check");
            report_tangent_error(load_factor);
          }
        if (ratio < tolerance || (linear_only && iteration == 1))
          {
            converged = true;
            break;
          }
        if (iteration == max_iterations)
          break;
        {
          TimerOutput::Scope t(timer, "linear solve");
          solve_linear_system();
        }
        displacement += correction;
        displacement_ghosted = displacement;
        if (line_search)
          assembled =
            search_along_correction(load_factor, ratio * external_force_norm);
      }
    if (!converged)
      {
        std::ostringstream message;
        if (dynamic)
          message << "The time step of size " << time_step;
        else
          message << "The load step to load factor " << load_factor;
        message << " did not converge in " << max_iterations
                << " Newton iterations.";
        throw RunError(message.str());
      }
  }



  template <int dim>
  bool
  ImplicitIntegrator<dim>::search_along_correction(
    const double load_factor,
    const double residual_norm)
  {
    // assemble() keeps f_ext in `correction`: save the direction first.
    const TrilinosWrappers::MPI::Vector direction(correction);
    constexpr unsigned int              max_cuts = 5;
    double                              step     = 1.;
    for (unsigned int cut = 0;; ++cut)
      {
        double trial = std::numeric_limits<double>::infinity();
        try
          {
            // With the tangent: the trial kept is the next Newton iterate.
            TimerOutput::Scope t(timer, "assemble");
            assemble(load_factor, !modified_newton);
            // Norms, not ratios: without external loads the scale is the
            // internal force, which the trial changes.
            trial = residual.l2_norm();
          }
        catch (const RunError &)
          {
            // An inverted point: too far along the correction.
          }
        if (trial < residual_norm || cut == max_cuts)
          {
            if (cut > 0)
              pcout << "    line search: 1/" << (1u << cut)
                    << " of the correction"
                    << (trial < residual_norm ? "" : ", no decrease")
                    << std::endl;
            return std::isfinite(trial);
          }
        step /= 2.;
        displacement.add(-step, direction);
        displacement_ghosted = displacement;
      }
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::update_points()
  {
    using Layout = PointLayout<dim>;
    std::vector<Tensor<1, dim>> du, v_n, a_n;
    for (const PointGroup &group : groups)
      {
        gather(group, du, v_n, a_n);
        for (unsigned int q = 0; q < group.particles.size(); ++q)
          {
            const Support<dim> &support  = group.supports[q];
            auto                particle = group.particles[q];
            const ArrayView<double> p = particle->get_properties();
            const Tensor<2, dim>    dF =
              PointAssembly<dim>::deformation_increment(support, du);
            const Tensor<2, dim> F_n = Layout::get_deformation_gradient(p);
            const Tensor<2, dim> F   = dF * F_n;
            const StepKinematics k   = step_kinematics(dF, F_n);
            const Material &material =
              *materials[static_cast<unsigned int>(p[Layout::material_id])];
            SymmetricTensor<2, 3>       stress     = Layout::get_stress(p);
            const SymmetricTensor<2, 3> stress_old = stress;
            material.update_stress(
              k,
              stress,
              ArrayView<double>(&p[Layout::internal_variables],
                                material.n_internal_variables()));
            // Stress work per reference volume over the step.
            p[Layout::work_density] +=
              0.5 *
              (determinant(F_n) * stress_old + determinant(F) * stress) *
              symmetrize(k.velocity_gradient) * k.dt;
            Layout::set_deformation_gradient(p, F);
            Layout::set_stress(p, stress);

            Tensor<1, dim> displacement_at_point;
            for (unsigned int i = 0; i < support.n_nodes; ++i)
              displacement_at_point += support.N[i] * du[i];
            if (dynamic)
              {
                // [I] eqs. 46-49: the points take the nodal acceleration at
                // the end of the step, and the Newmark velocity update.
                Tensor<1, dim> a_old, a_new;
                for (unsigned int i = 0; i < support.n_nodes; ++i)
                  {
                    a_old += support.N[i] * a_n[i];
                    a_new +=
                      support.N[i] * end_acceleration(du[i], v_n[i], a_n[i]);
                  }
                const Tensor<1, dim> dv = velocity_increment(a_old, a_new);
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    p[Layout::velocity + d] += dv[d];
                    p[points.acceleration_index() + d] = a_new[d];
                  }
              }
            particle->set_location(particle->get_location() +
                                   displacement_at_point);
          }
      }
    if (cloud)
      move_cloud();
  }



  template <int dim>
  void
  ImplicitIntegrator<dim>::gather(const PointGroup &           group,
                                  std::vector<Tensor<1, dim>> &du,
                                  std::vector<Tensor<1, dim>> &v_n,
                                  std::vector<Tensor<1, dim>> &a_n) const
  {
    const unsigned int n = group.dofs.size();
    du.resize(n / dim);
    v_n.resize(n / dim);
    a_n.resize(n / dim);
    for (unsigned int i = 0; i < n; ++i)
      {
        du[i / dim][i % dim] = displacement_ghosted(group.dofs[i]);
        if (dynamic)
          {
            v_n[i / dim][i % dim] = velocity_ghosted(group.dofs[i]);
            a_n[i / dim][i % dim] = acceleration_ghosted(group.dofs[i]);
          }
      }
  }



  template class ImplicitIntegrator<2>;
  template class ImplicitIntegrator<3>;
} // namespace mpm
