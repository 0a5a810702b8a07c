#include <mpm/assembly/grid_field.h>

#include <map>

namespace mpm
{
  namespace
  {
    /**
     * The registered fields by name. A function's static, so that it exists
     * before the first field registers itself, whichever file's statics run
     * first.
     */
    template <int dim>
    std::map<std::string, typename GridField<dim>::Factory> &
    registered_fields()
    {
      static std::map<std::string, typename GridField<dim>::Factory> fields;
      return fields;
    }
  } // namespace



  template <int dim>
  bool
  GridField<dim>::register_field(const std::string &name,
                                 const Factory &    factory)
  {
    const bool added = registered_fields<dim>().emplace(name, factory).second;
    AssertThrow(added,
                ExcMessage("Two grid fields are registered as '" + name +
                           "'."));
    return true;
  }



  template <int dim>
  std::unique_ptr<GridField<dim>>
  GridField<dim>::create(const std::string &   name,
                         const Grid<dim> &     grid,
                         const GridBasis<dim> &basis)
  {
    const auto field = registered_fields<dim>().find(name);
    AssertThrow(field != registered_fields<dim>().end(),
                ExcMessage("No grid field is registered as '" + name + "'."));
    return field->second(grid, basis);
  }



  template class GridField<2>;
  template class GridField<3>;
} // namespace mpm
