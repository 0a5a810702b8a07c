#ifndef mpm_boundary_nodal_condition_h
#define mpm_boundary_nodal_condition_h

#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>
#include <deal.II/lac/affine_constraints.h>

#include <mpm/base/force_report.h>

#include <array>
#include <cmath>
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
   * - the walls that hold the material only while it presses, with their
   *   normals and friction, for the active set (ContactActiveSet), and
   *   the forces on them at the end of an implicit step.
   * Each implementation connects its setup() to Grid::changed. Where
   * several conditions act on one node they act in the order of their
   * list, each on what the one before left: in the explicit solve, each
   * on the end velocity that the ones before it gave.
   */
  /**
   * How a wall that holds the material only while it presses holds a node
   * in an implicit step: not at all, along its normal only (the node
   * slides, against the Coulomb force), or in every direction.
   */
  enum class Hold
  {
    free,
    slip,
    stick
  };



  template <int dim>
  class NodalCondition : public ForceReport
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
     * Answer a change of the explicit acceleration of a field at a node
     * (the slot, GridNodes) made after constrain_explicit() (the blended
     * mass), in place: what the condition forbids goes, and what it
     * reports (a wall's force) follows what it takes. A fixed linear
     * projection of the velocity applies that projection; a wall its law
     * again, from the velocity the node would reach with the change.
     */
    virtual void
    constrain_change(const unsigned int node,
                     const unsigned int slot,
                     double *           change) const = 0;

    /**
     * The acceleration of a node at the start of a Newmark run, given its
     * velocity: by default, what constrain_velocity() leaves of it.
     */
    virtual void
    constrain_initial_acceleration(const unsigned int node,
                                   const double *,
                                   double *acceleration) const
    {
      constrain_velocity(node, acceleration);
    }

    /** An explicit step from `time` to time + dt begins. */
    virtual void
    begin_explicit_solve(const double, const double) const
    {}

    /**
     * The explicit nodal solve of one velocity field at a node, dt > 0:
     * `slot` names the field at the node (GridNodes), for what the
     * condition records of it; each field at a node is solved alone. On
     * entry `acceleration` is f / m, and the field would end the step with
     * velocity + dt acceleration. The condition changes the velocity, the acceleration
     * or both so that this end velocity meets it. The caller then gives
     * the node that end velocity, and the acceleration (end velocity -
     * velocity on entry) / dt, which holds the condition's reaction
     * impulse: constraining a alone would leave a point near a wall with
     * the velocity it had before the wall stopped its nodes, a velocity
     * the grid no longer has.
     */
    virtual void
    constrain_explicit(const unsigned int node,
                       const unsigned int slot,
                       const double       mass,
                       double *           velocity,
                       double *           acceleration,
                       const double       dt,
                       const double       time) const = 0;

    /**
     * Implicit schemes: the walls of a node that hold the material only
     * while it presses on them, and their friction (ContactActiveSet finds
     * which hold it in a step).
     */
    virtual unsigned int
    n_unilateral_walls(const unsigned int node) const = 0;

    /** The outward unit normal of the k-th such wall of a node. */
    virtual const Tensor<1, dim> &
    unilateral_normal(const unsigned int node, const unsigned int k) const;

    /**
     * Its Coulomb coefficient: 0 lets a held node slide freely, inf holds
     * it without slip.
     */
    virtual double
    friction_coefficient(const unsigned int node, const unsigned int k) const;

    /**
     * Implicit schemes: add the condition on the displacement of a node
     * whose components are `dofs`. `holds[k]` says how the k-th
     * unilateral wall of the node holds it in this step. Returns false
     * where the condition cannot be put as constraints on these dofs.
     */
    virtual bool
    add_constraints(const unsigned int                              node,
                    const std::array<types::global_dof_index, dim> &dofs,
                    const Hold *                                    holds,
                    AffineConstraints<double> &constraints) const = 0;

    /**
     * Implicit schemes, at the end of a step: forget the reactions of the
     * last step, then hear the force of the material on the k-th
     * unilateral wall of each node that material touches.
     */
    virtual void
    reset_reactions() const
    {}

    virtual void
    record_reaction(const unsigned int,
                    const unsigned int,
                    const Tensor<1, dim> &) const
    {}


  protected:
    /**
     * Hold the displacement of a node along the unit normal n of a wall:
     * the component along n's largest entry is fixed (a wall along an
     * axis) or tied to the others (a slanted wall, which must then be the
     * node's only one: `alone`). Returns false where that cannot be.
     */
    static bool
    hold_along_normal(const std::array<types::global_dof_index, dim> &dofs,
                      const Tensor<1, dim> &                          n,
                      const bool                                      alone,
                      AffineConstraints<double> &constraints)
    {
      unsigned int pivot = 0;
      for (unsigned int a = 1; a < dim; ++a)
        if (std::abs(n[a]) > std::abs(n[pivot]))
          pivot = a;
      if (constraints.is_constrained(dofs[pivot]))
        return true;
      const bool along_axis = std::abs(std::abs(n[pivot]) - 1.) < 1e-12;
      if (!along_axis && !alone)
        return false;
      constraints.add_line(dofs[pivot]);
      if (!along_axis)
        for (unsigned int a = 0; a < dim; ++a)
          if (a != pivot)
            constraints.add_entry(dofs[pivot], dofs[a], -n[a] / n[pivot]);
      return true;
    }

    /** Hold every component of a node's displacement. */
    static void
    hold_all(const std::array<types::global_dof_index, dim> &dofs,
             AffineConstraints<double> &                     constraints)
    {
      for (unsigned int a = 0; a < dim; ++a)
        if (!constraints.is_constrained(dofs[a]))
          constraints.add_line(dofs[a]);
    }
  };

  template <int dim>
  const Tensor<1, dim> &
  NodalCondition<dim>::unilateral_normal(const unsigned int,
                                         const unsigned int) const
  {
    AssertThrow(false, ExcMessage("This condition has no unilateral walls."));
    static const Tensor<1, dim> none;
    return none;
  }



  template <int dim>
  double
  NodalCondition<dim>::friction_coefficient(const unsigned int,
                                            const unsigned int) const
  {
    return 0.;
  }
} // namespace mpm

#endif
