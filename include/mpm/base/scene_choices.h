#ifndef mpm_base_scene_choices_h
#define mpm_base_scene_choices_h

#include <string>

namespace mpm
{
  /**
   * The choices of a scene that decide which of its parts may run
   * together: the time scheme (`Time stepping/Scheme`) and the method
   * (`Method`), read before anything is built. Each part refuses in its own
   * file what it cannot do with them (a check_scene() that throws
   * InputError), so that a new part brings its own refusals and the
   * simulator only builds.
   */
  struct SceneChoices
  {
    /** explicit, quasi-static or Newmark. */
    std::string scheme;
    /** MPM, GMM-MLS or GMM-LME. */
    std::string method;

    bool
    explicit_steps() const
    {
      return scheme == "explicit";
    }

    bool
    quasi_static() const
    {
      return scheme == "quasi-static";
    }

    bool
    newmark() const
    {
      return scheme == "Newmark";
    }

    /** Whether the points move on a cloud of nodes rather than the grid. */
    bool
    meshfree() const
    {
      return method != "MPM";
    }
  };
} // namespace mpm

#endif
