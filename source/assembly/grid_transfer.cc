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
    const Tensor<1, dim> &                          gravity)
    : points(points)
    , basis(basis)
    , nodes(nodes)
    , conditions(conditions)
    , gravity(gravity)
  {}



  template <int dim>
  void
  GridTransfer<dim>::add_force(const ArrayView<const double> &p,
                               const Support<dim> &           support,
                               const Point<dim> &             x,
                               double *                       forces,
                               const unsigned int             stride)
  {
    const double m = p[Layout::mass];
    // The supports are evaluated at the current positions: dF = I.
    PointAssembly<dim>::internal_force(
      support,
      nullptr,
      Layout::current_volume(p),
      Layout::get_stress(p),
      nullptr,
      nullptr,
      scratch,
      points.get_grid().is_axisymmetric() ? x[0] : 0.);
    const std::vector<double> &internal = scratch.force;
    Tensor<1, dim>             external = m * gravity;
    if (points.has_point_loads())
      for (unsigned int d = 0; d < dim; ++d)
        external[d] += p[points.point_load_index() + d];
    external *= load_factor;
    for (unsigned int i = 0; i < support.n_nodes; ++i)
      {
        double *f = forces + stride * support.nodes[i];
        for (unsigned int d = 0; d < dim; ++d)
          f[d] += support.N[i] * external[d] - internal[i * dim + d];
      }
  }



  template <int dim>
  void
  GridTransfer<dim>::project_mass_momentum(const bool with_force)
  {
    nodes.begin_projection(0, NodalLayout::n_components);
    if (nodal_density)
      nodal_density->begin_projection();
    for_each_point([&](const auto &particle, const Support<dim> &support) {
      const ArrayView<const double> p = particle->get_properties();
      const double                  m = p[Layout::mass];
      if (nodal_density)
        nodal_density->add_point(support, m, particle->get_location());
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          const unsigned int node = support.nodes[i];
          double *           v    = nodes.values_of(node);
          const double       Nm   = support.N[i] * m;
          v[NodalLayout::mass] += Nm;
          for (unsigned int d = 0; d < dim; ++d)
            v[NodalLayout::velocity + d] += Nm * p[Layout::velocity + d];
          nodes.mark_active(node);
        }
      if (with_force)
        add_force(p,
                  support,
                  particle->get_location(),
                  nodes.values_of(0) + NodalLayout::force,
                  NodalLayout::n_components);
    });
    nodes.finish_projection();
    if (nodal_density)
      nodal_density->compute_occupied_volumes(points.handler());
  }



  template <int dim>
  void
  GridTransfer<dim>::compute_nodal_velocity(const bool constrain)
  {
    for (const unsigned int node : nodes.nodes_to_solve())
      {
        // A point exactly on a cell face gives the opposite nodes N = 0 and
        // so zero mass and momentum; their velocity is zero, not 0/0.
        double *     v = nodes.values_of(node);
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
    if (constrain)
      for (const unsigned int node : nodes.nodes_to_solve())
        for (const NodalCondition<dim> *condition : conditions)
          if (condition->acts_on(node))
            condition->constrain_velocity(node,
                                          nodes.values_of(node) +
                                            NodalLayout::velocity);
  }



  template <int dim>
  void
  GridTransfer<dim>::compute_nodal_acceleration(const double dt)
  {
    const std::vector<unsigned int> &solve_nodes = nodes.nodes_to_solve();
    if (blended_mass)
      size_values_aside(solve_nodes);
    for (const unsigned int node : solve_nodes)
      {
        double *     v = nodes.values_of(node);
        const double m = v[NodalLayout::mass];
        for (unsigned int d = 0; d < dim; ++d)
          v[NodalLayout::force + d] =
            m > 0. ? v[NodalLayout::force + d] / m : 0.;
        apply_explicit_conditions(node, dt);
      }
    if (blended_mass)
      // The end velocities follow the accelerations' changes.
      correct_towards_consistent_mass(
        NodalLayout::force,
        true,
        0.5,
        true,
        [&](const unsigned int node, const double *change) {
          double *velocity = nodes.values_of(node) + NodalLayout::velocity;
          for (unsigned int d = 0; d < dim; ++d)
            velocity[d] += dt * change[d];
        });
  }



  template <int dim>
  void
  GridTransfer<dim>::apply_explicit_conditions(const unsigned int node,
                                               const double       dt)
  {
    double *     v        = nodes.values_of(node);
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
          condition->constrain_explicit(node, m, velocity, a, dt, time);
          constrained = true;
        }
    if (blended_mass)
      // The blended mass reads the acceleration the conditions leave,
      // without the impulse below: in MUSL a held node starts from an
      // unconstrained velocity, whose stop is no acceleration of the
      // material.
      for (unsigned int d = 0; d < dim; ++d)
        values_aside[node * dim + d] = a[d];
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
    const std::vector<unsigned int> &solve_nodes = nodes.nodes_to_solve();
    size_values_aside(solve_nodes);
    for (const unsigned int node : solve_nodes)
      for (unsigned int d = 0; d < dim; ++d)
        values_kept[node * dim + d] = nodes.values_of(node)[component + d];
    const std::vector<double> &w = field_aside ? values_aside : values_kept;

    nodes.begin_projection(component, dim);
    for_each_point([&](const auto &particle, const Support<dim> &support) {
      const double m       = particle->get_properties()[Layout::mass];
      double       mw[dim] = {};
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        for (unsigned int d = 0; d < dim; ++d)
          mw[d] += m * support.N[i] * w[support.nodes[i] * dim + d];
      for (unsigned int i = 0; i < support.n_nodes; ++i)
        {
          double *w = nodes.values_of(support.nodes[i]) + component;
          for (unsigned int d = 0; d < dim; ++d)
            w[d] += support.N[i] * mw[d];
        }
    });
    nodes.finish_projection();

    for (const unsigned int node : solve_nodes)
      {
        double *     values      = nodes.values_of(node) + component;
        const double m           = nodes.values_of(node)[NodalLayout::mass];
        double       change[dim] = {};
        if (m > 0.)
          {
            for (unsigned int d = 0; d < dim; ++d)
              change[d] = factor * (w[node * dim + d] - values[d] / m);
            if (constrained)
              for (const NodalCondition<dim> *condition : conditions)
                if (condition->acts_on(node))
                  condition->constrain_change(node, change);
          }
        for (unsigned int d = 0; d < dim; ++d)
          values[d] = values_kept[node * dim + d] + change[d];
        after_change(node, change);
      }
  }



  template <int dim>
  void
  GridTransfer<dim>::size_values_aside(
    const std::vector<unsigned int> &solve_nodes)
  {
    unsigned int n_nodes = 0;
    for (const unsigned int node : solve_nodes)
      n_nodes = std::max(n_nodes, node + 1);
    if (values_aside.size() < n_nodes * dim)
      {
        values_aside.resize(n_nodes * dim);
        values_kept.resize(n_nodes * dim);
      }
  }



  template <int dim>
  void
  GridTransfer<dim>::begin_step(const double dt)
  {
    for (const NodalCondition<dim> *condition : conditions)
      condition->begin_explicit_solve(time, dt);
  }



  template <int dim>
  void
  GridTransfer<dim>::compute_initial_acceleration()
  {
    for (const unsigned int node : nodes.nodes_to_solve())
      {
        double *     v = nodes.values_of(node);
        const double m = v[NodalLayout::mass];
        double *     a = v + NodalLayout::force;
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
