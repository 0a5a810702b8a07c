#ifndef mpm_grid_background_grid_h
#define mpm_grid_background_grid_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/distributed/tria.h>

#include <map>
#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * The background grid of a scene, described in the prm file: either one
   * of deal.II's GridGenerator functions by name and arguments, or a gmsh
   * file. Boundary ids get names, which the boundary conditions use.
   */
  template <int dim>
  class BackgroundGrid
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /** Parse the `Grid` subsection (the handler is at top level). */
    explicit BackgroundGrid(ParameterHandler &prm);

    /** Build the coarse grid, refine it, and check the boundary names. */
    void
    create(parallel::distributed::Triangulation<dim> &tria) const;

    /**
     * The boundary id of a named boundary; `entry` names the parameter that
     * used the name, for the message if it is unknown.
     */
    types::boundary_id
    boundary_id(const std::string &name, const std::string &entry) const;

  private:
    std::string                               generator;
    std::string                               arguments;
    std::string                               mesh_file;
    unsigned int                              n_refinements;
    std::map<std::string, types::boundary_id> boundary_names;
  };
} // namespace mpm

#endif
