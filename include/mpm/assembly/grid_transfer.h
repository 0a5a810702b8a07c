#ifndef mpm_assembly_grid_transfer_h
#define mpm_assembly_grid_transfer_h

#include <deal.II/base/tensor.h>

#include <mpm/assembly/field_contact.h>
#include <mpm/assembly/grid_field.h>
#include <mpm/assembly/grid_nodes.h>
#include <mpm/assembly/point_assembly.h>
#include <mpm/basis/grid_basis.h>
#include <mpm/boundary/nodal_condition.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>

namespace mpm
{
  using namespace dealii;

  /**
   * The transfers between material points and grid nodes that every scheme
   * shares: the lumped mass, momentum and force projections (P2G), the
   * nodal solve, and the loop that hands each point its support for the
   * grid-to-point updates (G2P).
   */
  template <int dim>
  class GridTransfer
  {
  public:
    using Layout      = PointLayout<dim>;
    using NodalLayout = typename GridNodes<dim>::NodalLayout;

    /**
     * `conditions` act at the nodes in the nodal solve, in this order.
     * `field_of_body` gives each body (by id) its velocity field in
     * `nodes`; empty: every point in field 0.
     */
    GridTransfer(MaterialPoints<dim> &                          points,
                 const GridBasis<dim> &                         basis,
                 GridNodes<dim> &                               nodes,
                 const std::vector<const NodalCondition<dim> *> &conditions,
                 const Tensor<1, dim> &                         gravity,
                 const std::vector<unsigned int> &field_of_body = {});

    /** The velocity field of the point with properties p. */
    unsigned int
    field_of(const ArrayView<const double> &p) const
    {
      return field_of_body.empty() ?
               0 :
               field_of_body[static_cast<unsigned int>(p[Layout::body_id])];
    }

    /**
     * Call f(particle, support) for every local point, points of one cell
     * after another, with the support of the point's current position.
     */
    template <typename Function>
    void
    for_each_point(const Function &f)
    {
      Support<dim> support;
      auto &       handler = points.handler();
      for (auto particle = handler.begin(); particle != handler.end();
           ++particle)
        {
          const unsigned int cell =
            particle->get_surrounding_cell()->active_cell_index();
          basis.evaluate(cell,
                         particle->get_reference_location(),
                         particle->get_properties(),
                         support);
          f(particle, support);
        }
    }

    /**
     * The factor on gravity and point loads in the forces projected from
     * now on (1 until set).
     */
    void
    set_load_factor(const double factor)
    {
      load_factor = factor;
    }

    /**
     * Build the grid fields that the laws read (Material::grid_fields()),
     * each once, in the order the laws name them; from now on each
     * projection of the mass projects them too.
     */
    void
    use_grid_fields(const std::vector<std::unique_ptr<Material>> &materials);

    /**
     * Solve the grid fields that obey an equation on the grid
     * (GridField::solve()): between the nodal solve and the stress update.
     * Collective.
     */
    void
    solve_grid_fields()
    {
      for (const auto &field : grid_fields)
        field->solve();
    }

    /**
     * Hand a point's law the values of the grid fields it reads, at the
     * point with this support: into kinematics.grid_fields.
     */
    void
    read_grid_fields(const unsigned int  material_id,
                     const Support<dim> &support,
                     StepKinematics &    kinematics) const
    {
      if (material_id >= fields_of_law.size())
        return;
      const std::vector<unsigned int> &fields = fields_of_law[material_id];
      for (unsigned int k = 0; k < fields.size(); ++k)
        kinematics.grid_fields[k] = grid_fields[fields[k]]->value(support);
    }

    /**
     * From now on, the fields meet through `contact` where they share
     * nodes (FieldContact): in the nodal solve and in the velocities that
     * the conditions constrain.
     */
    void
    couple_fields_by(FieldContact<dim> &contact)
    {
      field_contact = &contact;
    }

    /** Whether couple_fields_by() was called. */
    bool
    couples_fields() const
    {
      return field_contact != nullptr;
    }

    /**
     * From now on, compute_nodal_velocity() corrects the lumped velocity
     * projection towards the consistent one
     * (correct_towards_consistent_mass()).
     */
    void
    enable_corrected_velocity_projection()
    {
      corrected_velocity = true;
    }

    /**
     * From now on, compute_nodal_acceleration() takes half a Jacobi step
     * from the lumped mass towards the consistent one (the blended mass).
     */
    void
    enable_blended_mass()
    {
      blended_mass = true;
    }

    /** Whether enable_blended_mass() was called. */
    bool
    has_blended_mass() const
    {
      return blended_mass;
    }

    const Tensor<1, dim> &
    gravity_vector() const
    {
      return gravity;
    }

    /** The time at the start of the step, for conditions that change. */
    void
    set_time(const double t)
    {
      time = t;
    }

    /**
     * Lumped mass and momentum on the nodes, and, if `with_force`, the
     * internal force -sum V_p sigma_p grad N plus the external force
     * sum N (m_p g + f_p) times the load factor (f_p: point loads).
     */
    void
    project_mass_momentum(const bool with_force);

    /**
     * Momentum alone (the masses of the last projection stay). Each point
     * is first handed to update_point(particle, support), in the same pass:
     * it may change the point's velocity and read the nodal values of the
     * last solve, since the momenta are summed aside until the pass ends.
     * This saves MUSL a pass over the points.
     */
    template <typename Function>
    void
    project_momentum(const Function &update_point)
    {
      project_aside(NodalLayout::velocity,
                    [&](auto &particle, const Support<dim> &support) {
                      update_point(particle, support);
                      const ArrayView<const double> p =
                        particle->get_properties();
                      const double m = p[Layout::mass];
                      nodes.with_field(field_of(p), [&](const auto &field) {
                        for (unsigned int i = 0; i < support.n_nodes; ++i)
                          {
                            double *momentum =
                              values_aside.data() +
                              field.slot(support.nodes[i]) * dim;
                            for (unsigned int d = 0; d < dim; ++d)
                              momentum[d] +=
                                support.N[i] * m * p[Layout::velocity + d];
                          }
                      });
                    });
    }

    /**
     * Internal and external force alone. Each point is first handed to
     * update_point(particle, support), in the same pass: it may update the
     * point's stress, from which its force is then taken, and read the
     * nodal values of the last solve, since the forces are summed aside
     * until the pass ends. This saves USF a pass over the points.
     */
    template <typename Function>
    void
    project_force(const Function &update_point)
    {
      project_aside(NodalLayout::force,
                    [&](auto &particle, const Support<dim> &support) {
                      update_point(particle, support);
                      const ArrayView<const double> p =
                        particle->get_properties();
                      nodes.with_field(field_of(p), [&](const auto &field) {
                        add_force(p,
                                  support,
                                  particle->get_location(),
                                  [&](const unsigned int i) {
                                    return values_aside.data() +
                                           field.slot(support.nodes[i]) * dim;
                                  });
                      });
                    });
    }

    /**
     * v = p / m on every node (0 where m = 0), corrected if
     * enable_corrected_velocity_projection() was called, then, if
     * `constrain`, the contact between fields and the nodal conditions.
     */
    void
    compute_nodal_velocity(const bool constrain = true);

    /**
     * a = f / m in every field at every node; where fields meet, the stage
     * that couples them (couple_fields()); then the nodal conditions correct
     * each field so that v + dt a meets them, where v is the nodal velocity
     * as it stands (constrained or not); then v += dt a. With
     * enable_blended_mass(), the free nodes' a then moves towards the
     * consistent mass's.
     */
    void
    compute_nodal_acceleration(const double dt);

    /**
     * An explicit step from the time set by set_time() to it + dt begins:
     * the nodal conditions hear of it before any nodal solve of the step.
     */
    void
    begin_step(const double dt);

    /**
     * a = f / m on every node with what the nodal conditions forbid
     * removed, the velocity left alone: the start of a Newmark run.
     */
    void
    compute_initial_acceleration();

    /**
     * A nodal vector of one field (velocity or acceleration: `component`)
     * interpolated at a point.
     */
    Tensor<1, dim>
    interpolate(const Support<dim> &support,
                const unsigned int  field,
                const unsigned int  component) const
    {
      Tensor<1, dim> result;
      nodes.with_field(field, [&](const auto &values) {
        for (unsigned int i = 0; i < support.n_nodes; ++i)
          {
            const double *v = values.values(support.nodes[i]) + component;
            for (unsigned int d = 0; d < dim; ++d)
              result[d] += support.N[i] * v[d];
          }
      });
      return result;
    }

    /** Velocity gradient L = sum v_i (x) grad N_i of one field at a point. */
    Tensor<2, dim>
    velocity_gradient(const Support<dim> &support,
                      const unsigned int  field) const
    {
      Tensor<2, dim> L;
      nodes.with_field(field, [&](const auto &values) {
        for (unsigned int i = 0; i < support.n_nodes; ++i)
          {
            const double *v =
              values.values(support.nodes[i]) + NodalLayout::velocity;
            for (unsigned int a = 0; a < dim; ++a)
              for (unsigned int b = 0; b < dim; ++b)
                L[a][b] += v[a] * support.grad_N[i][b];
          }
      });
      return L;
    }

  private:
    /**
     * A nodal field w (in values_aside if `field_aside`, else what the
     * component holds) takes a step towards the consistent mass M_C = sum m_p N_p N_p^T: the change
     * factor (w - M_L^-1 M_C w) is added to the `dim` components from
     * `component` on, then handed to after_change(node, change). If
     * `constrained`, each node's change first passes through the conditions
     * on it, which take what they forbid and report the force of it
     * (NodalCondition::constrain_change()). Nodes without mass keep their
     * values. factor 1 is one Jacobi step from a lumped solve M_L w = r
     * towards M_C w = r; for a smooth mode of wave number k on a uniform 1D
     * grid M_L^-1 M_C has the eigenvalue 1 - e, e = (kh)^2 / 6.
     * - Velocity (factor 1, corrected projection, before the conditions: a
     *   wall node's lumped velocity is a true mean of its points' ones):
     *   the point velocities are sums of nodal updates, so what a step hands
     *   the next passes through P N = M_L^-1 M_C, which lengthens periods
     *   by (kh)^2 / 12, three times the lumped mass's own (kh)^2 / 24; after
     *   the step P N has the eigenvalue 1 - e^2.
     * - Acceleration (factor 1/2, blended mass, after the conditions):
     *   a = (1 + e / 2) M_L^-1 f is the solve with the mean of the lumped
     *   and the consistent mass to O(e^2), whose dispersion cancels to
     *   O((kh)^4).
     * The eigenvalues of M_L^-1 M_C lie in [0, 1] (N >= 0), so no mode
     * grows by more than 1 + factor; unconstrained, sum m_i w_i is kept,
     * since sum_i N_i(x_p) = 1.
     */
    template <typename Function>
    void
    correct_towards_consistent_mass(const unsigned int component,
                                    const bool         field_aside,
                                    const double       factor,
                                    const bool         constrained,
                                    const Function &   after_change);

    /**
     * One pass over the points in which add_point(particle, support) adds
     * each point's share of a nodal field (dim components from `component`
     * on) to values_aside, while the nodal values of the last solve can
     * still be read; the sums then become the field. A projection clears
     * the ghost nodes, so summing into the field itself would hide them.
     */
    template <typename Function>
    void
    project_aside(const unsigned int component, const Function &add_point)
    {
      const std::vector<unsigned int> &solve_slots = nodes.slots_to_solve();
      size_values_aside();
      for (const unsigned int slot : solve_slots)
        for (unsigned int d = 0; d < dim; ++d)
          values_aside[slot * dim + d] = 0.;
      for_each_point(add_point);
      nodes.begin_projection(component, dim);
      for (const unsigned int slot : solve_slots)
        for (unsigned int d = 0; d < dim; ++d)
          nodes.values_of(slot)[component + d] = values_aside[slot * dim + d];
      nodes.finish_projection();
    }

    /** values_aside and values_kept hold dim values for every slot. */
    void
    size_values_aside();

    /**
     * After a full projection: where the fields meet, the normals and
     * surfaces of their contact (FieldContact), from a pass over the
     * points. Collective.
     */
    void
    find_contact_geometry();

    /**
     * The stage of the nodal solve between a = f / m and the nodal
     * conditions, at the nodes where two or more fields have mass: where
     * fields meet, they exchange momentum here (FieldContact). Without a
     * contact, fields of bodies pass through each other.
     */
    void
    couple_fields(const double dt);

    /**
     * The nodal conditions on a slot whose a = f / m is known: they correct
     * the velocity v and a so that the end velocity v + dt a meets them,
     * and v becomes that end velocity.
     */
    void
    apply_explicit_conditions(const unsigned int slot, const double dt);

    /**
     * Add a point's gravity, load and internal force (with the hoop term in
     * an axisymmetric scene, which needs its position x) to its nodes: to
     * the dim values from target(i) on, for the i-th node of the support.
     */
    template <typename Target>
    void
    add_force(const ArrayView<const double> &p,
              const Support<dim> &           support,
              const Point<dim> &             x,
              const Target &                 target);
    MaterialPoints<dim> &           points;
    const GridBasis<dim> &          basis;
    GridNodes<dim> &                nodes;
    const std::vector<const NodalCondition<dim> *> conditions;
    const Tensor<1, dim>                           gravity;
    /** The index of the points' load (PointSlots "point_load"), if any. */
    const unsigned int                             point_load;
    /** By body id; empty: one field. */
    const std::vector<unsigned int>                field_of_body;
    double                                         load_factor = 1.;
    double                                         time        = 0.;
    /** The step begun last (begin_step()), 0 before the first. */
    double                                         step_dt     = 0.;
    FieldContact<dim> *                            field_contact = nullptr;
    typename PointAssembly<dim>::Scratch           scratch;
    /** The grid fields the laws read, and per law (by id) its fields' indices. */
    std::vector<std::unique_ptr<GridField<dim>>>   grid_fields;
    std::vector<std::vector<unsigned int>>         fields_of_law;
    bool                                           corrected_velocity = false;
    bool                                           blended_mass       = false;
    /**
     * dim values per slot: a nodal field to be corrected, or sums made
     * while the nodal values are still read.
     */
    std::vector<double> values_aside;
    /** dim values per slot: what a corrected component held before. */
    std::vector<double> values_kept;
  };



  template <int dim>
  template <typename Target>
  void
  GridTransfer<dim>::add_force(const ArrayView<const double> &p,
                               const Support<dim> &           support,
                               const Point<dim> &             x,
                               const Target &                 target)
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
      points.get_grid().geometry().hoop_radius(x));
    const std::vector<double> &internal = scratch.force;
    Tensor<1, dim>             external = m * gravity;
    if (point_load != numbers::invalid_unsigned_int)
      for (unsigned int d = 0; d < dim; ++d)
        external[d] += p[point_load + d];
    external *= load_factor;
    for (unsigned int i = 0; i < support.n_nodes; ++i)
      {
        double *f = target(i);
        for (unsigned int d = 0; d < dim; ++d)
          f[d] += support.N[i] * external[d] - internal[i * dim + d];
      }
  }
} // namespace mpm

#endif
