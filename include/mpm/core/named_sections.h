#ifndef mpm_core_named_sections_h
#define mpm_core_named_sections_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace mpm
{
  /**
   * Scenes name their materials and bodies: `Materials/Names = steel, soil`
   * followed by one subsection per name. ParameterHandler needs every
   * subsection declared before parsing, so the names are read in a first,
   * lenient pass (see Application) and the subsections declared from them.
   */
  /** The names of a scene's materials, bodies and obstacles. */
  struct SceneNames
  {
    std::vector<std::string> materials;
    std::vector<std::string> bodies;
    std::vector<std::string> obstacles;
  };

  namespace NamedSections
  {
    /** Declare the list entry `Names` in the current subsection. */
    void
    declare_names(dealii::ParameterHandler &prm,
                  const std::string &       default_names,
                  const std::string &       documentation);

    /**
     * Read `Names`; reject repeated names and, unless `may_be_empty`, an
     * empty list.
     */
    std::vector<std::string>
    parse_names(const dealii::ParameterHandler &prm,
                const std::string &             section_path,
                const bool                      may_be_empty = false);
  } // namespace NamedSections
} // namespace mpm

#endif
