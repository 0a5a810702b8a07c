#ifndef mpm_materials_material_library_h
#define mpm_materials_material_library_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
#include <mpm/grid/geometry.h>
#include <mpm/materials/material.h>

#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The laws of a scene, `Materials/<name>` for each name, by material id
   * (the order of the names), and the layout of the internal variables
   * that its points carry: as many as the largest law needs, named after
   * that law. Laws that share a variable keep it at the same index
   * (plastic_strain first), so every law's list must start the longest
   * one; the names in the output are then right for every point.
   */
  class MaterialLibrary
  {
  public:
    /** `Materials/<name>` for each name. */
    static void
    declare_parameters(ParameterHandler &              prm,
                       const std::vector<std::string> &names);

    /**
     * Build the laws (the handler is at top level); InputError for a bad
     * law, or for two laws whose internal variables cannot share a layout.
     */
    MaterialLibrary(ParameterHandler &prm, const std::vector<std::string> &names);

    /** A law that reads a grid field needs the explicit scheme (InputError). */
    void
    check_scene(const SceneChoices &choices) const
    {
      for (const auto &material : materials)
        for (const std::string &field : material->grid_fields())
          if (!choices.explicit_steps())
            throw InputError("Materials/" + material->name() + ": " + field +
                             " needs Time stepping/Scheme = explicit.");
    }

    /** A law whose stress follows the density is for loose fill, not a plate. */
    template <int dim>
    void
    check_geometry(const Geometry<dim> &geometry) const
    {
      for (const auto &material : materials)
        if (geometry.free_faces() && (!material->grid_fields().empty() ||
                                      material->stress_follows_density()))
          throw InputError("Materials/" + material->name() + ": a law whose "
                           "stress follows the density is for loose fill, "
                           "not a plate; Grid/Geometry = plane stress takes "
                           "the other laws.");
    }

    const std::vector<std::unique_ptr<Material>> &
    laws() const
    {
      return materials;
    }

    /** The internal variables every point carries, by name. */
    const std::vector<std::string> &
    internal_variable_names() const
    {
      return internal_names;
    }

  private:
    std::vector<std::unique_ptr<Material>> materials;
    std::vector<std::string>               internal_names;
  };
} // namespace mpm

#endif
