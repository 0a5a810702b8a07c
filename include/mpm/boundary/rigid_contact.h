#ifndef mpm_boundary_rigid_contact_h
#define mpm_boundary_rigid_contact_h

#include <deal.II/base/tensor.h>

#include <mpm/boundary/coulomb_contact.h>
#include <mpm/boundary/nodal_condition.h>
#include <mpm/grid/grid.h>

#include <unordered_map>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * What the friction walls and the rigid obstacles share: rigid surfaces
   * that hold the material at grid nodes with one Coulomb law
   * (CoulombContact), and the record of the force of the material on them,
   * one reaction per surface at each node and velocity field it acted on in
   * the last nodal solve. The records give the time series its forces and
   * the traction files their rows; the blended mass corrects them
   * (follow_change()).
   *
   * A surface is what the derived class counts as one: a wall at one node
   * (FrictionWalls), or an obstacle (RigidObstacles).
   */
  template <int dim>
  class RigidContact : public NodalCondition<dim>
  {
  protected:
    /**
     * One surface at one field of one node, with the law that gave it in an
     * explicit solve (inactive where the surface did not hold the node).
     */
    struct Reaction
    {
      unsigned int        node;
      unsigned int        slot;
      unsigned int        surface;
      double              normal = 0.;
      Tensor<1, dim>      tangential;
      Tensor<1, dim>      force;
      CoulombContact<dim> law;
    };

    explicit RigidContact(const Grid<dim> &grid)
      : grid(grid)
    {}

    /** Forget the reactions of the last solve. */
    void
    clear_reactions() const
    {
      reactions.clear();
      first_reaction.clear();
    }

    /**
     * The explicit nodal solve of one surface at a slot: its Coulomb law
     * for the relative velocity `relative` at the end of the step and the
     * unit normal `into_surface`, recorded, active or not (the blended
     * mass's change may press an inactive one).
     */
    const CoulombContact<dim> &
    act(const unsigned int    node,
        const unsigned int    slot,
        const unsigned int    surface,
        const Tensor<1, dim> &relative,
        const Tensor<1, dim> &into_surface,
        const double          friction,
        const double          mass,
        const double          dt) const;

    /**
     * A force of the material on a surface at a node measured apart from
     * the explicit solve (the implicit schemes' reactions), split along
     * the unit normal `outward` and across it.
     */
    void
    record(const unsigned int    node,
           const unsigned int    surface,
           const Tensor<1, dim> &outward,
           const Tensor<1, dim> &force) const;

    /**
     * The blended mass's change of a slot's acceleration: each surface that
     * stood there in this solve answers it with its law again, in the order
     * they acted (CoulombContact::follow_change()).
     */
    void
    follow_change(const unsigned int slot, double *change) const;

    /**
     * The reactions at this rank's owned nodes, ordered by surface (and in
     * the order they were recorded within one), so that sums over them do
     * not depend on the order of the nodal solve.
     */
    std::vector<const Reaction *>
    owned_reactions_by_surface() const;

    /** The reactions at this rank's owned nodes, in the order recorded. */
    std::vector<const Reaction *>
    owned_reactions() const;

    const Grid<dim> &grid;

  private:
    mutable std::vector<Reaction> reactions;
    /** Where the reactions of a slot start (they follow each other). */
    mutable std::unordered_map<unsigned int, unsigned int> first_reaction;
  };
} // namespace mpm

#endif
