#ifndef mpm_boundary_nodal_condition_h
#define mpm_boundary_nodal_condition_h

#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/affine_constraints.h>

#include <array>
#include <string>
#include <vector>

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
   * list, each on what the one before left: in the explicit solve, each
   * on the end velocity that the ones before it gave.
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

    /** An explicit step from `time` to time + dt begins. */
    virtual void
    begin_explicit_solve(const double, const double) const
    {}

    /**
     * The explicit nodal solve at a node, dt > 0. On entry `acceleration`
     * is f / m, and the node would end the step with velocity + dt
     * acceleration. The condition changes the velocity, the acceleration
     * or both so that this end velocity meets it. The caller then gives
     * the node that end velocity, and the acceleration (end velocity -
     * velocity on entry) / dt, which holds the condition's reaction
     * impulse: constraining a alone would leave a point near a wall with
     * the velocity it had before the wall stopped its nodes, a velocity
     * the grid no longer has.
     */
    virtual void
    constrain_explicit(const unsigned int node,
                       const double       mass,
                       double *           velocity,
                       double *           acceleration,
                       const double       dt,
                       const double       time) const = 0;

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

    /** Names of the forces the condition reports in the time series. */
    virtual std::vector<std::string>
    force_names() const
    {
      return {};
    }

    /** Those forces at the last nodal solve, on every rank. Collective. */
    virtual std::vector<double>
    forces() const
    {
      return {};
    }

    /**
     * At an output time: write what the condition reports along its
     * walls into `directory`, named with the step. Collective.
     */
    virtual void
    write_tractions(const std::string &, const unsigned int) const
    {}
  };
} // namespace mpm

#endif
