#ifndef mpm_points_point_slots_h
#define mpm_points_point_slots_h

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <string>
#include <vector>

namespace mpm
{
  /**
   * The optional properties of a scene's material points, after the laws'
   * internal variables (PointLayout): each is asked for by name, by the part
   * that uses it, before the points are built (the implicit schemes' point
   * acceleration, the loads' point load, the adaptive grid's record of the
   * plastic strain), and laid out in the order asked. Its name is the name
   * of the property in the point output.
   */
  class PointSlots
  {
  public:
    struct Slot
    {
      std::string  name;
      unsigned int n_components;
      /** Whether the components are those of a vector (output). */
      bool is_vector;
      /** The first component's offset from the end of the internal variables. */
      unsigned int offset;
    };

    /**
     * Ask for a slot; asking again for one of that name returns the one
     * there is.
     */
    void
    request(const std::string &name,
            const unsigned int n_components,
            const bool         is_vector)
    {
      if (has(name))
        {
          AssertThrow(find(name).n_components == n_components,
                      dealii::ExcInternalError());
          return;
        }
      slots.push_back({name, n_components, is_vector, n_components_total()});
    }

    bool
    has(const std::string &name) const
    {
      return std::any_of(slots.begin(), slots.end(), [&](const Slot &slot) {
        return slot.name == name;
      });
    }

    /** The slot of that name (InternalError if none was asked for). */
    const Slot &
    find(const std::string &name) const
    {
      for (const Slot &slot : slots)
        if (slot.name == name)
          return slot;
      AssertThrow(false,
                  dealii::ExcMessage("No point slot '" + name +
                                     "' was asked for."));
      return slots.front();
    }

    /** The components of all slots. */
    unsigned int
    n_components_total() const
    {
      unsigned int n = 0;
      for (const Slot &slot : slots)
        n += slot.n_components;
      return n;
    }

    const std::vector<Slot> &
    all() const
    {
      return slots;
    }

  private:
    std::vector<Slot> slots;
  };
} // namespace mpm

#endif
