#include <mpm/base/input_error.h>
#include <mpm/materials/material_library.h>

#include <algorithm>

namespace mpm
{
  void
  MaterialLibrary::declare_parameters(ParameterHandler &              prm,
                                      const std::vector<std::string> &names)
  {
    prm.enter_subsection("Materials");
    for (const auto &name : names)
      {
        prm.enter_subsection(name);
        Material::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }



  MaterialLibrary::MaterialLibrary(ParameterHandler &              prm,
                                   const std::vector<std::string> &names)
  {
    prm.enter_subsection("Materials");
    for (const auto &name : names)
      {
        prm.enter_subsection(name);
        materials.push_back(Material::create(prm, name, "Materials/" + name));
        prm.leave_subsection();
      }
    prm.leave_subsection();

    std::string longest;
    for (const auto &m : materials)
      if (m->n_internal_variables() > internal_names.size())
        {
          internal_names = m->internal_variable_names();
          longest        = m->name();
        }
    for (const auto &m : materials)
      {
        const std::vector<std::string> &own = m->internal_variable_names();
        if (!std::equal(own.begin(), own.end(), internal_names.begin()))
          throw InputError("Materials '" + m->name() + "' (" +
                           comma_separated(own) + ") and '" + longest + "' (" +
                           comma_separated(internal_names) +
                           ") keep different internal variables, so one "
                           "scene cannot hold both: the point output would "
                           "name them wrongly.");
      }
  }
} // namespace mpm
