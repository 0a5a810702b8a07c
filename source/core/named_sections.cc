#include <mpm/base/input_error.h>
#include <mpm/core/named_sections.h>

#include <algorithm>

namespace mpm
{
  namespace NamedSections
  {
    void
    declare_names(dealii::ParameterHandler &prm,
                  const std::string &       default_names,
                  const std::string &       documentation)
    {
      prm.declare_entry("Names",
                        default_names,
                        dealii::Patterns::List(dealii::Patterns::Anything()),
                        documentation);
    }



    std::vector<std::string>
    parse_names(const dealii::ParameterHandler &prm,
                const std::string &             section_path,
                const bool                      may_be_empty)
    {
      const std::vector<std::string> names =
        dealii::Utilities::split_string_list(prm.get("Names"));
      if (names.empty() && !may_be_empty)
        throw InputError(section_path +
                         "/Names is empty: name at least one, and describe "
                         "each in a subsection of that name.");
      for (unsigned int i = 0; i < names.size(); ++i)
        {
          if (names[i] == "Names")
            throw InputError(section_path + "/Names may not contain 'Names'.");
          if (std::find(names.begin(), names.begin() + i, names[i]) !=
              names.begin() + i)
            throw InputError(section_path + "/Names lists '" + names[i] +
                             "' twice.");
        }
      return names;
    }
  } // namespace NamedSections
} // namespace mpm
