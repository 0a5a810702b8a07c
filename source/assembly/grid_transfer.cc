#include <mpm/assembly/grid_transfer.h>

#include <algorithm>

namespace mpm
{
  template <int dim>
  GridTransfer<dim>::GridTransfer(
    MaterialPoints<dim> &                           points,
    const GridBasis<dim> &                          basis,
    GridNodes<dim> &                                nodes,
    const std::vector<const NodalCondition<dim> *> &conditions,
    const Tensor<1, dim> &                          gravity,
    const std::vector<unsigned int> &               field_of_body)
    : points(points)
    , basis(basis)
    , nodes(nodes)
    , conditions(conditions)
    , gravity(gravity)
    , point_load(points.has_slot("point_load") ?
                   points.slot_index("point_load") :
                   numbers::invalid_unsigned_int)
    , field_of_body(field_of_body)
  {
    for (const unsigned int field : field_of_body)
      AssertThrow(field < nodes.n_fields(), ExcInternalError());
    AssertThrow(nodes.n_fields() == 1 || !field_of_body.empty(),
                ExcInternalError());
  }



  template <int dim>
  void
  GridTransfer<dim>::project_mass_momentum(const bool with_force)
  {
    if (field_contact)
      field_contact->begin_projection(nodes);
    nodes.begin_projection(0, NodalLayout::n_components);
    for (const auto &field : grid_fields)
      field->begin_projection();
    for_each_point([&](const auto &particle, const Support<dim> &support) {
      const ArrayView<const double> p = particle->get_properties();
      const double                  m = p[Layout::mass];
      for (const auto &grid_field : grid_fields)
        grid_field->add_point(support, p, particle->get_location());
      nodes.with_field(field_of(p), [&](const auto &field) {
        for (unsigned int i = 0; i < support.n_nodes; ++i)
          {
            double *     v  = field.claim(support.nodes[i]);
            const double Nm = support.N[i] * m;
            v[NodalLayout::mass] += Nm;
            for (unsigned int d = 0; d < dim; ++d)
              v[NodalLayout::velocity + d] += Nm * p[Layout::velocity + d];
          }
        if (field_contact)
          {
            const double volume = Layout::current_volume(p);
            for (unsigned int i = 0; i < support.n_nodes; ++i)
              field_contact->add_volume_gradient(field.slot(support.nodes[i]),
                                                 volume,
                                                 support.grad_N[i]);
          }
        if (with_force)
          add_force(p,
                    support,
                    particle->get_location(),
                    [&](const unsigned int i) {
                      return field.values(support.nodes[i]) + NodalLayout::force;
                    });
      });
    });
    nodes.finish_projection();
    for (const auto &field : grid_fields)
      field->finish_projection(points.handler());
    if (field_contact)
      find_contact_geometry();
  }



  template <int dim>
  void
  GridTransfer<dim>::find_contact_geometry()
  {
    field_contact->find_normals(nodes);
    if (field_contact->fields_meet())
      for_each_point([&](const auto &particle, const Support<dim> &support) {
        const ArrayView<const double> p = particle->get_properties();
        field_contact->add_point(field_of(p),
                                 support,
                                 particle->get_location(),
                                 p);
      });
    field_contact->finish_surfaces(nodes);
  }



  template <int dim>
  void
  GridTransfer<dim>::use_grid_fields(
    const std::vector<std::unique_ptr<Material>> &materials)
  {
    std::vector<std::string> names;
    fields_of_law.clear();
    for (const auto &material : materials)
      {
        const std::vector<std::string> wanted = material->grid_fields();
        AssertThrow(wanted.size() <= StepKinematics::max_grid_fields,
                    ExcInternalError());
        fields_of_law.emplace_back();
        for (const std::string &name : wanted)
          {
            const auto known = std::find(names.begin(), names.end(), name);
            fields_of_law.back().push_back(known - names.begin());
            if (known == names.end())
              {
                names.push_back(name);
                grid_fields.push_back(GridField<dim>::create(
                  name, points.get_grid(), basis));
              }
          }
      }
  }



  template <int dim>
  void
  GridTransfer<dim>::compute_nodal_velocity(const bool constrain)
  {
    for (const unsigned int slot : nodes.slots_to_solve())
      {
        // A point exactly on a cell face gives the opposite nodes N = 0 and
        // so zero mass and momentum; their velocity is zero, not 0/0.
        double *     v = nodes.values_of(slot);
        const double m = v[NodalLayout::mass];
        for (unsigned int d = 0; d < dim; ++d)
          v[NodalLayout::velocity + d] =
            m > 0. ? v[NodalLayout::velocity + d] / m : 0.;
      }
    if (corrected_velocity)
      correct_towards_consistent_mass(NodalLayout::velocity,
                                      false,
                                      1.,
                                      false,
                                      [](const unsigned int, const double *) {
                                      });
    if (constrain && field_contact)
      field_contact->couple(nodes, step_dt, false);
    if (constrain)
      for (const unsigned int slot : nodes.slots_to_solve())
        for (const NodalCondition<dim> *condition : conditions)
          if (condition->acts_on(nodes.node_of_slot(slot)))
            condition->constrain_velocity(nodes.node_of_slot(slot),
                                          nodes.values_of(slot) +
                                            NodalLayout::velocity);
  }



  template <int dim>
  void
  GridTransfer<dim>::compute_nodal_acceleration(const double dt)
  {
    const std::vector<unsigned int> &solve_slots = nodes.slots_to_solve();
    if (blended_mass)
      size_values_aside();
    for (const unsigned int slot : solve_slots)
      {
        double *     v = nodes.values_of(slot);
        const double m = v[NodalLayout::mass];
        for (unsigned int d = 0; d < dim; ++d)
          v[NodalLayout::force + d] =
            m > 0. ? v[NodalLayout::force + d] / m : 0.;
      }
    couple_fields(dt);
    for (const unsigned int slot : solve_slots)
      apply_explicit_conditions(slot, dt);
    if (blended_mass)
      // The end velocities follow the accelerations' changes.
      correct_towards_consistent_mass(
        NodalLayout::force,
        true,
        0.5,
        true,
        [&](const unsigned int slot, const double *change) {
          double *velocity = nodes.values_of(slot) + NodalLayout::velocity;
          for (unsigned int d = 0; d < dim; ++d)
            velocity[d] += dt * change[d];
        });
  }



  template <int dim>
  void
  GridTransfer<dim>::couple_fields(const double dt)
  {
    if (field_contact)
      field_contact->couple(nodes, dt, true);
  }



  template <int dim>
  void
  GridTransfer<dim>::apply_explicit_conditions(const unsigned int slot,
                                               const double       dt)
  {
    const unsigned int node   = nodes.node_of_slot(slot);
    double *           v      = nodes.values_of(slot);
    const double m        = v[NodalLayout::mass];
    double *     a        = v + NodalLayout::force;
    double *     velocity = v + NodalLayout::velocity;
    double       start[dim];
    for (unsigned int d = 0; d < dim; ++d)
      start[d] = velocity[d];
    bool constrained = false;
    for (const NodalCondition<dim> *condition : conditions)
      if (condition->acts_on(node))
        {
          condition->constrain_explicit(node, slot, m, velocity, a, dt, time);
          constrained = true;
        }
    if (blended_mass)
      // The blended mass reads the acceleration the conditions leave,
      // without the impulse below: in MUSL a held node starts from an
      // unconstrained velocity, whose stop is no acceleration of the
      // material.
      for (unsigned int d = 0; d < dim; ++d)
        values_aside[slot * dim + d] = a[d];
    for (unsigned int d = 0; d < dim; ++d)
      {
        // a takes the conditions' reaction impulse (velocity - start)
        // / dt, so that v_start + dt a is the end velocity too.
        const double end = velocity[d] + dt * a[d];
        if (constrained)
          a[d] += (velocity[d] - start[d]) / dt;
        velocity[d] = end;
      }
  }



  template <int dim>
  template <typename Function>
  void
  GridTransfer<dim>::correct_towards_consistent_mass(
    const unsigned int component,
    const bool         field_aside,
    const double       factor,
    const bool         constrained,
    const Function &   after_change)
  {
    // M_C w is summed into the component, since a projection clears the
    // ghost nodes, so what the component held is kept aside first.
    const std::vector<unsigned int> &solve_slots = nodes.slots_to_solve();
    size_values_aside();
    for (const unsigned int slot : solve_slots)
      for (unsigned int d = 0; d < dim; ++d)
        values_kept[slot * dim + d] = nodes.values_of(slot)[component + d];
    const std::vector<double> &w = field_aside ? values_aside : values_kept;

    nodes.begin_projection(component, dim);
    for_each_point([&](const auto &particle, const Support<dim> &support) {
      const ArrayView<const double> p       = particle->get_properties();
      const double                  m       = p[Layout::mass];
      const unsigned int            field   = field_of(p);
      double                        mw[dim] = {};
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        for (unsigned int d = 0; d < dim; ++d)
          mw[d] += m * support.N[i] *
                   w[nodes.slot(support.nodes[i], field) * dim + d];
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          double *w =
            nodes.values_of(nodes.slot(support.nodes[i], field)) + component;
          for (unsigned int d = 0; d < dim; ++d)
            w[d] += support.N[i] * mw[d];
        }
    });
    nodes.finish_projection();

    for (const unsigned int slot : solve_slots)
      {
        const unsigned int node        = nodes.node_of_slot(slot);
        double *           values      = nodes.values_of(slot) + component;
        const double       m           = nodes.values_of(slot)[NodalLayout::mass];
        double             change[dim] = {};
        if (m > 0.)
          {
            for (unsigned int d = 0; d < dim; ++d)
              change[d] = factor * (w[slot * dim + d] - values[d] / m);
            if (constrained)
              for (const NodalCondition<dim> *condition : conditions)
                if (condition->acts_on(node))
                  condition->constrain_change(node, slot, change);
          }
        for (unsigned int d = 0; d < dim; ++d)
          values[d] = values_kept[slot * dim + d] + change[d];
        after_change(slot, change);
      }
  }



  template <int dim>
  void
  GridTransfer<dim>::size_values_aside()
  {
    const std::size_t n_values = std::size_t(nodes.n_slots()) * dim;
    if (values_aside.size() < n_values)
      {
        values_aside.resize(n_values);
        values_kept.resize(n_values);
      }
  }



  template <int dim>
  void
  GridTransfer<dim>::begin_step(const double dt)
  {
    step_dt = dt;
    for (const NodalCondition<dim> *condition : conditions)
      condition->begin_explicit_solve(time, dt);
  }



  template <int dim>
  void
  GridTransfer<dim>::compute_initial_acceleration()
  {
    for (const unsigned int slot : nodes.slots_to_solve())
      {
        const unsigned int node = nodes.node_of_slot(slot);
        double *           v    = nodes.values_of(slot);
        const double       m    = v[NodalLayout::mass];
        double *           a    = v + NodalLayout::force;
        double velocity[dim];
        for (unsigned int d = 0; d < dim; ++d)
          {
            a[d]        = m > 0. ? a[d] / m : 0.;
            velocity[d] = m > 0. ? v[NodalLayout::velocity + d] / m : 0.;
          }
        for (const NodalCondition<dim> *condition : conditions)
          if (condition->acts_on(node))
            condition->constrain_initial_acceleration(node, velocity, a);
      }
  }



  template class GridTransfer<2>;
  template class GridTransfer<3>;
} // namespace mpm
