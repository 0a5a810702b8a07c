#include <deal.II/base/mpi.h>
#include <deal.II/lac/vector.h>

#include <Epetra_CrsMatrix.h>

#include <mpm/assembly/point_assembly.h>
#include <mpm/base/input_error.h>
#include <mpm/materials/plane_stress.h>
#include <mpm/time/implicit_assembler.h>

#include <algorithm>
#include <cmath>

namespace mpm
{
  template <int dim>
  ImplicitAssembler<dim>::ImplicitAssembler(
    const MaterialPoints<dim> &                   points,
    const std::vector<std::unique_ptr<Material>> &materials,
    const Tensor<1, dim> &                        gravity,
    const Newmark &                               newmark)
    : points(points)
    , materials(materials)
    , gravity(gravity)
    , newmark(newmark)
  {}



  template <int dim>
  void
  ImplicitAssembler<dim>::assemble(ImplicitState<dim> &state,
                                   const double        load_factor,
                                   const bool          with_tangent)
  {
    using Layout = PointLayout<dim>;
    state.residual     = 0.;
    state.correction   = 0.; // holds f_ext here, for the convergence measure
    if (state.keeps_unconstrained_residual)
      state.unconstrained_residual = 0.;
    if (with_tangent)
      {
        state.tangent = 0.;
        state.factorization.reset();
      }
    double internal_force_square = 0.;
    double momentum_rate_square  = 0.;
    bool   inverted              = false;
    bool   out_of_plane_failed   = false;
    const Geometry<dim> &geometry     = points.get_grid().geometry();
    const bool           plane_stress = geometry.free_faces();
    const unsigned int   point_load   = points.slot_index("point_load");

    FullMatrix<double>          cell_tangent;
    Vector<double>              cell_residual, cell_external;
    FullMatrix<double>          point_tangent;
    typename PointAssembly<dim>::Scratch scratch;
    std::vector<Tensor<1, dim>> du, v_n, a_n, a_node;
    std::vector<double>         internal;
    const double                mass_stiffness =
      state.dynamic ? (1. - newmark.bossak_alpha) /
                        (newmark.beta * state.time_step * state.time_step) :
                      0.;

    for (const auto &group : state.groups)
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
        state.gather(group, du, v_n, a_n);

        for (unsigned int q = 0; q < group.particles.size(); ++q)
          {
            const Support<dim> &          support = group.supports[q];
            const ArrayView<const double> p =
              group.particles[q]->get_properties();
            const Tensor<2, dim>          dF =
              PointAssembly<dim>::deformation_increment(support, du);
            const Point<dim> &position = group.particles[q]->get_location();
            const double      hoop     = hoop_increment(geometry, support, du, position);
            StepKinematics k = step_kinematics(dF, hoop, p, state.time_step);
            const Material &material =
              *materials[static_cast<unsigned int>(p[Layout::material_id])];
            const SymmetricTensor<2, 3> old_stress = Layout::get_stress(p);
            const ArrayView<const double> old_internal(
              &p[Layout::internal_variables], material.n_internal_variables());
            SymmetricTensor<2, 3> stress = old_stress;
            internal.assign(old_internal.begin(), old_internal.end());
            const ArrayView<double> new_internal(internal.data(),
                                                 internal.size());
            if (!(determinant(k.F_new) > 0.))
              inverted = true;
            else if (!PlaneStress::update_stress(
                       material, k, stress, new_internal, plane_stress))
              out_of_plane_failed = true;
            SymmetricTensor<4, 3> c;
            if (with_tangent && !inverted && !out_of_plane_failed)
              {
                c = material.spatial_tangent(k, old_stress, old_internal);
                if (plane_stress)
                  c = PlaneStress::condense(c);
              }
            PointAssembly<dim>::internal_force(
              support,
              &dF,
              weight * Layout::current_volume(p, k.F_new),
              stress,
              &c,
              with_tangent ? &own_tangent : nullptr,
              scratch,
              hoop * geometry.hoop_radius(position));
            const std::vector<double> &point_force = scratch.force;

            for (unsigned int i = 0; i < support.n_nodes; ++i)
              for (unsigned int a = 0; a < dim; ++a)
                {
                  const double external =
                    load_factor * support.N[i] *
                    (p[point_load + a] +
                     p[Layout::mass] * gravity[a]);
                  cell_external(i * dim + a) += external;
                  cell_residual(i * dim + a) +=
                    external - point_force[i * dim + a];
                }
            if (with_tangent && !single_point)
              cell_tangent.add(1., point_tangent);

            if (state.dynamic)
              {
                // Inertia with the Newmark (Bossak) nodal acceleration, and
                // its derivative. Consistent: m_p a(x_p) at the point, mass
                // m_p N_i N_k ([I] eq. 30). Lumped: m_p N_i a_i, mass
                // m_p N_i on the diagonal.
                a_node.resize(support.n_nodes);
                Tensor<1, dim> a_point;
                for (unsigned int k = 0; k < support.n_nodes; ++k)
                  {
                    a_node[k] = (1. - newmark.bossak_alpha) *
                                  newmark.end_acceleration(
                                    du[k], v_n[k], a_n[k], state.time_step) +
                                newmark.bossak_alpha * a_n[k];
                    a_point += support.N[k] * a_node[k];
                  }
                const double m = p[Layout::mass];
                momentum_rate_square +=
                  m * m * Layout::get_velocity(p).norm_square() /
                  (state.time_step * state.time_step);
                for (unsigned int i = 0; i < support.n_nodes; ++i)
                  {
                    const double mass_i = support.N[i] * m;
                    for (unsigned int a = 0; a < dim; ++a)
                      cell_residual(i * dim + a) -=
                        mass_i *
                        (newmark.lumped_mass ? a_node[i][a] : a_point[a]);
                    if (!with_tangent)
                      continue;
                    for (unsigned int k = 0; k < support.n_nodes; ++k)
                      if (!newmark.lumped_mass || k == i)
                        for (unsigned int a = 0; a < dim; ++a)
                          cell_tangent(i * dim + a, k * dim + a) +=
                            mass_i * (newmark.lumped_mass ? 1. : support.N[k]) *
                            mass_stiffness;
                  }
              }
          }

        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          if (!state.constraints.is_constrained(dofs[i]))
            internal_force_square +=
              (cell_external(i) - cell_residual(i)) *
              (cell_external(i) - cell_residual(i));
        if (with_tangent && !state.sliding_nodes.empty())
          add_friction_tangent(state, dofs, cell_tangent);
        if (with_tangent && !add_to_tangent(state, dofs, cell_tangent))
          state.constraints.distribute_local_to_global(
            cell_tangent, cell_residual, dofs, state.tangent, state.residual);
        else
          state.constraints.distribute_local_to_global(cell_residual,
                                                       dofs,
                                                       state.residual);
        state.constraints.distribute_local_to_global(cell_external,
                                                     dofs,
                                                     state.correction);
        if (state.keeps_unconstrained_residual)
          state.unconstrained_residual.add(dofs, cell_residual);
      }
    // A node that no point reaches has an empty row: a unit diagonal
    // keeps the matrix regular (its dofs are held at zero).
    if (with_tangent)
      for (const types::global_dof_index dof0 : state.unreached_node_dofs)
        for (unsigned int a = 0; a < dim; ++a)
          state.tangent.add(dof0 + a, dof0 + a, 1.);
    // Compress before a throw: entries buffered for other ranks would
    // otherwise survive `= 0.` and join the next assembly (a line search
    // goes on after a failed trial).
    if (with_tangent)
      state.tangent.compress(VectorOperation::add);
    state.residual.compress(VectorOperation::add);
    state.correction.compress(VectorOperation::add);
    if (state.keeps_unconstrained_residual)
      state.unconstrained_residual.compress(VectorOperation::add);
    if (Utilities::MPI::logical_or(inverted, points.get_communicator()))
      throw RunError("A Newton iterate inverted a material point (det F <= "
                     "0).");
    if (Utilities::MPI::logical_or(out_of_plane_failed,
                                   points.get_communicator()))
      throw RunError("At a Newton iterate no out-of-plane stretch of a "
                     "material point gives sigma_zz = 0 (plane stress).");
    // Collective (compress) where some rank has a sliding node.
    if (state.keeps_unconstrained_residual &&
        Utilities::MPI::logical_or(!state.sliding_nodes.empty(),
                                   points.get_communicator()))
      add_friction_forces(state);

    // The scale of the forces ([B] eq. 31): the external load, or, where
    // none acts (a scene driven by its boundaries or its initial motion),
    // the internal forces cell by cell, and in dynamic runs the momentum
    // rate m v_n / dt, whichever is larger. A residual r changes the step's
    // velocities by the order of r dt / m, so against m v_n / dt the ratio
    // is of the order of the relative velocity error; without it a body in
    // free flight would compare round-off with round-off and never converge.
    state.external_force_norm = state.correction.l2_norm();
    if (!(state.external_force_norm > 0.))
      {
        Tensor<1, 2> squares;
        squares[0] = internal_force_square;
        squares[1] = momentum_rate_square;
        squares    = Utilities::MPI::sum(squares, points.get_communicator());
        state.external_force_norm = std::sqrt(std::max(squares[0], squares[1]));
      }
  }



  template <int dim>
  void
  ImplicitAssembler<dim>::add_friction_tangent(
    const ImplicitState<dim> &                  state,
    const std::vector<types::global_dof_index> &dofs,
    FullMatrix<double> &                        cell_tangent) const
  {
    // K = -dr/du, and the friction -mu (n . r_node) s adds
    // mu s (n . dr_node/du) = -mu s (n . K_node) to the node's rows.
    const unsigned int n = dofs.size();
    std::vector<double> pressing_row(n);
    for (unsigned int i = 0; i < n; i += dim)
      {
        const auto [first, last] = state.sliding_nodes.equal_range(dofs[i]);
        for (auto slide = first; slide != last; ++slide)
          {
            const auto &node = slide->second;
            for (unsigned int k = 0; k < n; ++k)
              {
                pressing_row[k] = 0.;
                for (unsigned int b = 0; b < dim; ++b)
                  pressing_row[k] += node.outward[b] * cell_tangent(i + b, k);
              }
            for (unsigned int a = 0; a < dim; ++a)
              for (unsigned int k = 0; k < n; ++k)
                cell_tangent(i + a, k) -=
                  node.friction * node.direction[a] * pressing_row[k];
          }
      }
  }



  template <int dim>
  void
  ImplicitAssembler<dim>::add_friction_forces(ImplicitState<dim> &state) const
  {
    const TrilinosWrappers::MPI::Vector residual_at_nodes =
      state.wall_reactions(points.get_communicator());
    Vector<double>                       force(dim);
    std::vector<types::global_dof_index> node_dofs(dim);
    // By the owner of each node's first dof. Linear in r, whatever its
    // sign, to match the tangent: a node that pulls at convergence is
    // released by the active set.
    for (const auto &[dof0, node] : state.sliding_nodes)
      {
        if (!state.owned_dofs.is_element(dof0))
          continue;
        double pressing = 0.;
        for (unsigned int a = 0; a < dim; ++a)
          pressing += residual_at_nodes(dof0 + a) * node.outward[a];
        for (unsigned int a = 0; a < dim; ++a)
          {
            force(a)     = -node.friction * pressing * node.direction[a];
            node_dofs[a] = dof0 + a;
          }
        state.constraints.distribute_local_to_global(force,
                                                     node_dofs,
                                                     state.residual);
      }
    state.residual.compress(VectorOperation::add);
  }



  template <int dim>
  bool
  ImplicitAssembler<dim>::add_to_tangent(
    ImplicitState<dim> &                        state,
    const std::vector<types::global_dof_index> &dofs,
    const FullMatrix<double> &                  matrix)
  {
    for (const types::global_dof_index dof : dofs)
      if (!state.owned_dofs.is_element(dof) ||
          state.constraints.is_constrained(dof))
        return false;
    // deal.II gives only const access to the Epetra matrix; its values
    // belong to `tangent`, which is not const. FillComplete sorts each
    // row's local column indices, so a group's columns sorted the same way
    // are found in one pass along each row (a column not found throws).
    Epetra_CrsMatrix &epetra =
      const_cast<Epetra_CrsMatrix &>(state.tangent.trilinos_matrix());
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



  template class ImplicitAssembler<2>;
  template class ImplicitAssembler<3>;
} // namespace mpm
