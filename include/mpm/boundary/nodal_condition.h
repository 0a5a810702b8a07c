#ifndef mpm_boundary_nodal_condition_h
#define mpm_boundary_nodal_condition_h

#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/affine_constraints.h>

#include <array>

namespace mpm
{
  using namespace dealii;

  /**
   * What acts on the nodes of the background grid: walls (fixed, slip,
   * contact), and whatever else holds or pushes the material at nodes. A
   * condition is asked at each place where nodal conditions act, for the
   * nodes it acts on (Grid node ids):
   * - the explicit nodal solve, with the node's mass, velocity,
   *   acceleration, the step and the time;
   * - the implicit schemes' constraints on the node's displacement;
   * - the outward normal of a wall that holds the material only while it
   *   presses, for the active set (ContactActiveSet) and its gaps.
   * Each implementation connects its setup() to Grid::changed. Where
   * several conditions act on one node they act in the order of their
   * list, each on what the one before left (today a node has at most
   * one: the grid's walls combine theirs at corners themselves).
   */
  template <int dim>
  class NodalCondition
  {
  public:
    virtual ~NodalCondition() = default;

    /** Find the nodes the condition acts on. */
    virtual void
    setup() = 0;

    /** Whether some node is held only while the material presses. */
    virtual bool
    has_unilateral_nodes() const = 0;

    /** Whether the condition acts on this node. */
    virtual bool
    acts_on(const unsigned int node) const = 0;

    /**
     * Remove what the condition forbids from a nodal velocity (or any
     * nodal vector), in place.
     */
    virtual void
    constrain_velocity(const unsigned int node, double *velocity) const = 0;

    /**
     * The explicit nodal solve at a node: `acceleration` is f / m on
     * entry; on return v + dt a meets the condition, with v the nodal
     * `velocity` as it stands, which becomes v + dt a if
     * `advance_velocity`. With dt = 0 the condition acts on a alone.
     */
    virtual void
    constrain_explicit(const unsigned int node,
                       const double       mass,
                       double *           velocity,
                       double *           acceleration,
                       const double       dt,
                       const double       time,
                       const bool         advance_velocity) const = 0;

    /**
     * Implicit schemes: add the condition on the displacement of a node
     * whose components are `dofs`. `held` says whether a unilateral wall
     * holds the node in this step (ContactActiveSet). Returns false where
     * the condition cannot be put as constraints on these dofs.
     */
    virtual bool
    add_constraints(const unsigned int                              node,
                    const std::array<types::global_dof_index, dim> &dofs,
                    const bool                                      held,
                    AffineConstraints<double> &constraints) const = 0;

    /**
     * The outward unit normal of a wall that holds the node only while the
     * material presses on it, or nullptr if the node has no such wall.
     */
    virtual const Tensor<1, dim> *
    unilateral_normal(const unsigned int node) const = 0;
  };
} // namespace mpm

#endif
