#ifndef mpm_boundary_contact_active_set_h
#define mpm_boundary_contact_active_set_h

#include <boost/serialization/array.hpp>
#include <boost/serialization/map.hpp>
#include <boost/serialization/set.hpp>
#include <boost/serialization/utility.hpp>

#include <array>
#include <map>
#include <set>
#include <utility>
#include <vector>

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
   *   towards it (which nodes it engages is the system's geometry); and
   *   the first step starts with every pair held that material touches.
   * - A pair changes at most once a step, so that a node that pulls while
   *   held but moves into the wall when free does not flip for ever.
   * - A held pair sticks or slides (walls with friction). It is engaged
   *   sliding where it moved along the wall in the step (on a frictionless
   *   wall always) and sticking otherwise; it starts to
   *   slide when the wall's tangential force exceeds mu times its normal
   *   force, in the direction the material pushes, and sticks again when
   *   it would slide backwards. This too changes at most once a step.
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

    /**
     * The unit direction in which a held pair slides (3 entries, the
     * unused ones zero), or nullptr where it sticks.
     */
    const std::array<double, 3> *
    slide_direction(const unsigned int node, const unsigned int wall) const
    {
      const auto found = sliding.find({node, wall});
      return found == sliding.end() ? nullptr : &found->second;
    }

    /** Start a step: every pair may change once again. */
    void
    begin_step()
    {
      changed.clear();
      changed_sliding.clear();
    }

    /** Whether a step has been solved with this set. */
    bool
    has_started() const
    {
      return started;
    }

    /** A step was solved with this set. */
    void
    mark_started()
    {
      started = true;
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
      sliding.erase({node, wall});
      changed.insert({node, wall});
      return true;
    }

    /**
     * Hold a free pair where material closes on the wall, unless it has
     * changed in this step. Returns whether it was engaged.
     */
    bool
    engage(const unsigned int           node,
           const unsigned int           wall,
           const bool                   slides    = false,
           const std::array<double, 3> &direction = {})
    {
      if (holds(node, wall) || has_changed(node, wall))
        return false;
      held.insert({node, wall});
      if (slides)
        sliding[{node, wall}] = direction;
      changed.insert({node, wall});
      return true;
    }

    /**
     * Let a held, sticking pair slide along `direction` (a unit vector),
     * unless its sliding has changed in this step. Returns whether it
     * does.
     */
    bool
    start_sliding(const unsigned int           node,
                  const unsigned int           wall,
                  const std::array<double, 3> &direction)
    {
      if (!holds(node, wall) || sliding.count({node, wall}) > 0 ||
          changed_sliding.count({node, wall}) > 0)
        return false;
      sliding[{node, wall}] = direction;
      changed_sliding.insert({node, wall});
      return true;
    }

    /** Let a sliding pair stick, unless that changed in this step. */
    bool
    stop_sliding(const unsigned int node, const unsigned int wall)
    {
      if (sliding.count({node, wall}) == 0 ||
          changed_sliding.count({node, wall}) > 0)
        return false;
      sliding.erase({node, wall});
      changed_sliding.insert({node, wall});
      return true;
    }

    /**
     * Turn the direction of a sliding pair (3D: the direction follows the
     * motion along the wall); not counted as a change.
     */
    void
    turn(const unsigned int           node,
         const unsigned int           wall,
         const std::array<double, 3> &direction)
    {
      sliding.at({node, wall}) = direction;
    }

    /**
     * Before the first step: a free pair that material touches is held
     * (sliding on a frictionless wall, sticking on others), not counted
     * as a change.
     */
    void
    hold_from_start(const unsigned int node,
                    const unsigned int wall,
                    const bool         slides)
    {
      if (held.insert({node, wall}).second && slides)
        sliding[{node, wall}] = {};
    }

    /**
     * Between steps: a held pair that no material touches any more is
     * free in the new step (not counted as a change).
     */
    void
    let_go(const unsigned int node, const unsigned int wall)
    {
      held.erase({node, wall});
      sliding.erase({node, wall});
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
      remembered         = held;
      remembered_sliding = sliding;
      remembered_started = started;
    }

    void
    restore()
    {
      held    = remembered;
      sliding = remembered_sliding;
      started = remembered_started;
    }

    /**
     * The held pairs for which `keep(node, wall)` is true, in a form that
     * outlives the node numbers: per pair the node's coordinates (3
     * entries, from `position`), the wall, 1 if it slides, and the
     * direction (3 entries); and a last entry 1 if a step was solved. The
     * nodes of a grid that is repartitioned are numbered anew, and pass to
     * other ranks.
     */
    template <class Position, class Keep>
    std::vector<double>
    by_position(const Position &position, const Keep &keep) const
    {
      std::vector<double> pairs;
      for (const auto &pair : held)
        if (keep(pair.first, pair.second))
        {
          const std::array<double, 3> x = position(pair.first);
          pairs.insert(pairs.end(), x.begin(), x.end());
          pairs.push_back(pair.second);
          const auto found = sliding.find(pair);
          pairs.push_back(found != sliding.end());
          const std::array<double, 3> d =
            found != sliding.end() ? found->second : std::array<double, 3>{};
          pairs.insert(pairs.end(), d.begin(), d.end());
        }
      pairs.push_back(started);
      return pairs;
    }

    /**
     * The set from by_position() of each rank (empty where a rank gave
     * none), for the nodes this rank knows: `node(x)` gives the node at
     * coordinates x, or numbers::invalid_unsigned_int (all bits set). The
     * current set is replaced.
     */
    template <class Node>
    void
    renumber(const std::vector<std::vector<double>> &by_rank, const Node &node)
    {
      *this = ContactActiveSet();
      for (const std::vector<double> &pairs : by_rank)
        if (!pairs.empty())
        {
          constexpr unsigned int size = 8;
          for (unsigned int k = 0; k + size < pairs.size(); k += size)
            {
              const unsigned int n =
                node(std::array<double, 3>{{pairs[k], pairs[k + 1], pairs[k + 2]}});
              if (n == static_cast<unsigned int>(-1))
                continue;
              const std::pair<unsigned int, unsigned int> pair = {
                n, static_cast<unsigned int>(pairs[k + 3])};
              held.insert(pair);
              if (pairs[k + 4] == 1.)
                sliding[pair] = {{pairs[k + 5], pairs[k + 6], pairs[k + 7]}};
            }
          started = started || pairs.back() == 1.;
        }
    }

    /** The held pairs and how they slide, for Checkpoint. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &held &sliding &started;
    }

  private:
    std::set<std::pair<unsigned int, unsigned int>> held;
    std::set<std::pair<unsigned int, unsigned int>> changed;
    std::set<std::pair<unsigned int, unsigned int>> remembered;
    std::map<std::pair<unsigned int, unsigned int>, std::array<double, 3>>
      sliding, remembered_sliding;
    std::set<std::pair<unsigned int, unsigned int>> changed_sliding;
    bool started = false, remembered_started = false;
  };
} // namespace mpm

#endif
