#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <mpm/core/input_error.h>
#include <mpm/grid/background_grid.h>

#include <fstream>
#include <set>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  BackgroundGrid<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Grid");
    prm.declare_entry(
      "Generator",
      "subdivided_hyper_rectangle",
      Patterns::Anything(),
      "Name of a deal.II GridGenerator function that makes the coarse grid, "
      "e.g. subdivided_hyper_rectangle or hyper_cube. Ignored if a Mesh file "
      "is given.");
    prm.declare_entry(
      "Arguments",
      "20, 20 : 0, 0 : 1, 1 : true",
      Patterns::Anything(),
      "Arguments of the generator, ':'-separated, as "
      "GridGenerator::generate_from_name_and_arguments reads them. For "
      "subdivided_hyper_rectangle: cells per direction : lower corner : "
      "upper corner : colorize. Colorize = true gives the faces x-, x+, y-, "
      "y+ (, z-, z+) the boundary ids 0, 1, 2, 3 (, 4, 5).");
    prm.declare_entry("Mesh file",
                      "",
                      Patterns::Anything(),
                      "A gmsh .msh file with the coarse grid, relative to the "
                      "parameter file. Physical tags on its boundary become "
                      "boundary ids.");
    prm.declare_entry("Global refinements",
                      "0",
                      Patterns::Integer(0, 20),
                      "Times every cell of the coarse grid is refined.");
    prm.declare_entry(
      "Boundary names",
      "left: 0, right: 1, bottom: 2, top: 3, back: 4, front: 5",
      Patterns::Map(Patterns::Anything(), Patterns::Integer(0, 254)),
      "Names for boundary ids, 'name: id, ...', used by the boundary "
      "conditions. The default matches a colorized hyper_rectangle.");
    prm.leave_subsection();
  }



  template <int dim>
  BackgroundGrid<dim>::BackgroundGrid(ParameterHandler &prm)
  {
    prm.enter_subsection("Grid");
    generator     = prm.get("Generator");
    arguments     = prm.get("Arguments");
    mesh_file     = prm.get("Mesh file");
    n_refinements = prm.get_integer("Global refinements");
    for (const auto &entry :
         Utilities::split_string_list(prm.get("Boundary names"), ','))
      {
        const auto pair = Utilities::split_string_list(entry, ':');
        boundary_names[pair[0]] = Utilities::string_to_int(pair[1]);
      }
    prm.leave_subsection();
  }



  template <int dim>
  void
  BackgroundGrid<dim>::create(
    parallel::distributed::Triangulation<dim> &tria) const
  {
    if (!mesh_file.empty())
      {
        std::ifstream in(mesh_file);
        if (!in)
          throw InputError("Grid/Mesh file = '" + mesh_file +
                           "' cannot be opened.");
        GridIn<dim> grid_in(tria);
        try
          {
            grid_in.read_msh(in);
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream info;
            e.print_info(info);
            throw InputError("Grid/Mesh file = '" + mesh_file +
                             "' is not a gmsh mesh deal.II can read: " +
                             info.str());
          }
      }
    else
      {
        try
          {
            GridGenerator::generate_from_name_and_arguments(tria,
                                                            generator,
                                                            arguments);
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream info;
            e.print_info(info);
            throw InputError("Grid/Generator = '" + generator +
                             "' with Grid/Arguments = '" + arguments +
                             "' does not make a grid: " + info.str());
          }
      }
    tria.refine_global(n_refinements);
  }



  template <int dim>
  types::boundary_id
  BackgroundGrid<dim>::boundary_id(const std::string &name,
                                   const std::string &entry) const
  {
    const auto found = boundary_names.find(name);
    if (found == boundary_names.end())
      {
        std::string known;
        for (const auto &n : boundary_names)
          known += (known.empty() ? "" : ", ") + n.first;
        throw InputError(entry + " names the boundary '" + name +
                         "', which Grid/Boundary names does not define. "
                         "Known names: " +
                         known + ".");
      }
    return found->second;
  }



  template class BackgroundGrid<2>;
  template class BackgroundGrid<3>;
} // namespace mpm
