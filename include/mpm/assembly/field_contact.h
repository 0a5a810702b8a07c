#ifndef mpm_assembly_field_contact_h
#define mpm_assembly_field_contact_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/assembly/grid_nodes.h>
#include <mpm/base/force_report.h>
#include <mpm/base/scene_choices.h>
#include <mpm/basis/support.h>
#include <mpm/bodies/body.h>
#include <mpm/grid/grid.h>
#include <mpm/points/point_layout.h>

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Contact between bodies: each contact group of bodies (Bodies/<name>/
   * Contact group) moves in its own velocity field at the nodes
   * (GridNodes), and where two fields have mass at a node they meet
   * through one Coulomb law (CoulombContact), as in Bardenhagen et al.
   * (2000) and the multi-field codes after it (Uintah, NairnMPM, CB-Geo):
   * - the node's centre-of-mass velocity is what the two fields share;
   * - the normal from field A to field B is a volume gradient, sum V_p
   *   grad N_i(x_p) over a field's points, which points out of the field
   *   where it ends: A's or B's, whichever the two fields' surfaces near
   *   the node are further apart along (the default: a separating axis),
   *   or the larger one, or their difference;
   * - the fields touch only while they approach and their surfaces,
   *   measured from the points, are less than the gap tolerance apart at
   *   the end of the step: a point's surface along n lies at x_p . n
   *   +- r_p, half the extent of its deformed box along n. Approach alone
   *   would make bodies meet a cell early, as soon as they share a node;
   * - A then keeps the centre-of-mass velocity plus what the Coulomb law
   *   leaves of its relative velocity (nothing where it sticks, the
   *   tangential part less mu times the normal part where it slips), and
   *   B gets the opposite momentum: the exchange conserves momentum
   *   exactly, and the normal velocities of the two fields become equal.
   *   A tied pair moves together wherever its surfaces are within the
   *   gap, approaching or not.
   *
   * The law acts on the end velocities of the nodal solve (the force it
   * takes goes into the acceleration, which the points receive) and, at
   * the projections of velocity that the conditions constrain, on the
   * velocities. The geometry (normals, surfaces) is found once per step,
   * after the full projection: points move only at the end of a step.
   *
   * A node where three or more fields have mass (where three bodies meet)
   * takes its pairs one after the other, each along the larger of its
   * two gradients, by approach alone.
   */
  template <int dim>
  class FieldContact : public ForceReport
  {
  public:
    /** The section `Contact`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * The groups of the bodies (Body::contact_group()), numbered in the
     * order they first appear, and the section `Contact` (the handler at
     * top level). Connects to Grid::changed.
     */
    FieldContact(ParameterHandler &             prm,
                 const std::vector<Body<dim>> &bodies,
                 const Grid<dim> &              grid);

    /** The number of groups, and of velocity fields at the nodes. */
    unsigned int
    n_groups() const
    {
      return group_names.size();
    }

    /** Each body's field (by body id); empty with one group. */
    const std::vector<unsigned int> &
    field_of_body() const
    {
      return body_fields;
    }

    /** Contact between bodies needs the explicit scheme (InputError). */
    void
    check_scene(const SceneChoices &choices) const;

    /**
     * A projection of all nodal values begins (before
     * GridNodes::begin_projection()): the volume gradients of the slots
     * of the last one are cleared.
     */
    void
    begin_projection(const GridNodes<dim> &nodes);

    /**
     * A point of volume V adds V grad N to the volume gradient of its
     * field at a node of its support, the slot, in the projection.
     */
    void
    add_volume_gradient(const unsigned int    slot,
                        const double          volume,
                        const Tensor<1, dim> &grad_N)
    {
      if (slot_gradients.size() < (slot + 1) * dim)
        slot_gradients.resize(2 * (slot + 1) * dim, 0.);
      for (unsigned int d = 0; d < dim; ++d)
        slot_gradients[slot * dim + d] += volume * grad_N[d];
    }

    /**
     * After the projection: the nodes where fields meet and the candidate
     * normals there. Collective.
     */
    void
    find_normals(const GridNodes<dim> &nodes);

    /** Whether fields meet at some node of this rank. */
    bool
    fields_meet() const
    {
      return !shared.empty();
    }

    /**
     * Hand the surfaces a point of `field` at x with properties p and this
     * support (after find_normals()).
     */
    void
    add_point(const unsigned int             field,
              const Support<dim> &           support,
              const Point<dim> &             x,
              const ArrayView<const double> &p);

    /**
     * The points' surfaces, over the ranks, and at each node the normal
     * of the candidates along which they are furthest apart. Collective.
     */
    void
    finish_surfaces(const GridNodes<dim> &nodes);

    /**
     * The law at every node where fields meet, in a step of dt. With
     * `end_of_step`, on the end velocities v + dt a of the nodal solve:
     * a takes the change, and the forces are recorded for forces();
     * otherwise on the velocities, which it changes.
     */
    void
    couple(GridNodes<dim> &nodes, const double dt, const bool end_of_step);

    /**
     * Per pair of groups A-B (in the order of the groups): the force of A
     * on B at the last nodal solve, its components, the sum of its normal
     * parts and of the lengths of its tangential parts over the nodes.
     */
    std::vector<std::string>
    force_names() const override;

    std::vector<double>
    forces() const override;

    /**
     * Per pair A-B, `a_on_b_forces_<step>.csv`: each node where A pressed
     * on B in the last nodal solve, its normal and tangential force.
     */
    void
    write_tractions(const std::string &directory,
                    const unsigned int step) const override;

  private:
    using Layout = PointLayout<dim>;

    enum class NormalRule
    {
      separating_gradient,
      largest_gradient,
      gradient_difference
    };

    /** How a pair of groups meets. */
    struct PairLaw
    {
      double friction = 0.;
      bool   tied     = false;
    };

    /** Read Contact/Pairs into pair_laws. */
    void
    parse_pairs(const std::string &text, const PairLaw &default_law);

    /** The index of the pair of groups a < b. */
    unsigned int
    pair_index(const unsigned int a, const unsigned int b) const
    {
      return a * n_groups() + b;
    }

    /**
     * The unit normal from field a to field b at the k-th shared node by
     * the rule's `candidate` (0: a's gradient, 1: minus b's; the larger
     * one, or the difference, for the other rules); zero where the
     * gradients give none.
     */
    Tensor<1, dim>
    normal(const unsigned int k,
           const unsigned int a,
           const unsigned int b,
           const unsigned int candidate) const;

    /** The volume gradient of a field at the k-th shared node. */
    Tensor<1, dim>
    gradient(const unsigned int k, const unsigned int field) const
    {
      Tensor<1, dim> g;
      for (unsigned int d = 0; d < dim; ++d)
        g[d] = gradients[(k * n_groups() + field) * dim + d];
      return g;
    }

    static constexpr unsigned int none = numbers::invalid_unsigned_int;

    const Grid<dim> &         grid;
    std::vector<std::string>  group_names;
    std::vector<unsigned int> body_fields;
    /** By pair_index(a, b), a < b. */
    std::vector<PairLaw>      pair_laws;
    NormalRule                normal_rule = NormalRule::separating_gradient;
    /** The gap below which surfaces touch, as a fraction of the cell. */
    double                    gap_tolerance = 0.;

    /** dim values per slot: sum V_p grad N_i of the slot's field. */
    std::vector<double> slot_gradients;

    /** The nodes where fields meet, and per node its index there. */
    std::vector<unsigned int> shared;
    std::vector<unsigned int> shared_index;
    /** Per shared node: the gradient of every field, n_groups dim values. */
    std::vector<double> gradients;
    /**
     * Per shared node where exactly two fields meet: the lower field, the
     * higher one, the two candidate normals between them, and once the
     * surfaces are known the normal and the surfaces' distance along it;
     * elsewhere lower = none.
     */
    std::vector<unsigned int>   lower_field, upper_field;
    std::vector<Tensor<1, dim>> candidates;
    std::vector<Tensor<1, dim>> normals;
    std::vector<double>         distances;
    /**
     * Per shared node and candidate, two values: the furthest surface of
     * the lower field along the candidate, max (x . n + r), and minus the
     * nearest of the upper one, max -(x . n - r).
     */
    std::vector<double> surfaces;

    /**
     * Per pair, recorded at the owned nodes by the last nodal solve: the
     * force (dim values), the normal and the tangential sums.
     */
    std::vector<double> recorded;
    /**
     * The same node by node, at the owned nodes: position, then the
     * normal and tangential force, per pair.
     */
    std::vector<std::vector<std::array<double, dim + 2>>> node_forces;

    boost::signals2::scoped_connection grid_changed;
  };
} // namespace mpm

#endif
