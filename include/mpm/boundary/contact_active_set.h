#ifndef mpm_boundary_contact_active_set_h
#define mpm_boundary_contact_active_set_h

#include <boost/serialization/set.hpp>
#include <boost/serialization/utility.hpp>

#include <set>
#include <utility>

namespace mpm
{
  /**
   * Which nodes a wall holds, for walls that hold the material only while
   * it presses on them: the one rule of the implicit schemes, for grid
   * nodes (GridSystem) and for the nodes of the meshfree cloud
   * (CloudSystem) alike.
   *
   * - A held (node, wall) pair lets go when the wall force on the material
   *   would pull it out of the grid.
   * - A free pair is engaged where material closes on the wall: a point
   *   that the step brings within half its spacing of the wall, moving
   *   towards it (which nodes it engages is the system's geometry).
   * - A pair changes at most once a step, so that a node that pulls while
   *   held but moves into the wall when free does not flip for ever.
   * - A step that fails is retried from the set it started with.
   *
   * Nodes are the system's node numbers; walls are numbered by the system
   * (a grid node has one contact wall, number 0).
   */
  class ContactActiveSet
  {
  public:
    bool
    holds(const unsigned int node, const unsigned int wall) const
    {
      return held.count({node, wall}) > 0;
    }

    /** Start a step: every pair may change once again. */
    void
    begin_step()
    {
      changed.clear();
    }

    /**
     * Let a held pair go if `pull`, the wall force on the material along
     * the wall's outward normal, is positive, and it has not changed in
     * this step. Returns whether it was released.
     */
    bool
    release_if_pulling(const unsigned int node,
                       const unsigned int wall,
                       const double       pull)
    {
      if (!(pull > 0.) || !holds(node, wall) || has_changed(node, wall))
        return false;
      held.erase({node, wall});
      changed.insert({node, wall});
      return true;
    }

    /**
     * Hold a free pair where material closes on the wall, unless it has
     * changed in this step. Returns whether it was engaged.
     */
    bool
    engage(const unsigned int node, const unsigned int wall)
    {
      if (holds(node, wall) || has_changed(node, wall))
        return false;
      held.insert({node, wall});
      changed.insert({node, wall});
      return true;
    }

    /**
     * Between steps: a held pair that no material touches any more is
     * free in the new step (not counted as a change).
     */
    void
    let_go(const unsigned int node, const unsigned int wall)
    {
      held.erase({node, wall});
    }

    bool
    has_changed(const unsigned int node, const unsigned int wall) const
    {
      return changed.count({node, wall}) > 0;
    }

    /** Keep the set as it is, to put it back if the step fails. */
    void
    remember()
    {
      remembered = held;
    }

    void
    restore()
    {
      held = remembered;
    }

    /** The held pairs, for Checkpoint. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &held;
    }

  private:
    std::set<std::pair<unsigned int, unsigned int>> held;
    std::set<std::pair<unsigned int, unsigned int>> changed;
    std::set<std::pair<unsigned int, unsigned int>> remembered;
  };
} // namespace mpm

#endif
