#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_cartesian.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

#include <mpm/base/input_error.h>
#include <mpm/grid/grid.h>

#include <fstream>
#include <limits>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  Grid<dim>::declare_parameters(ParameterHandler &prm)
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
    Geometry<dim>::declare_parameters(prm);
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
  Grid<dim>::Grid(ParameterHandler &prm, const MPI_Comm communicator)
    : scene_geometry([&prm]() {
      prm.enter_subsection("Grid");
      const Geometry<dim> geometry(prm);
      prm.leave_subsection();
      return geometry;
    }())
    // Rebuilt from the coarse mesh at every repartition, so that the cells'
    // local order, and with it the node numbering and every sum over
    // cells, depends on the partition only, not on how it was reached: a
    // run continued from a checkpoint restores the partition directly.
    , triangulation(communicator,
                    Triangulation<dim>::none,
                    parallel::distributed::Triangulation<
                      dim>::mesh_reconstruction_after_repartitioning)
    , node_element(1)
    , node_dof_handler(triangulation)
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
  Grid<dim>::create()
  {
    if (!mesh_file.empty())
      {
        std::ifstream in(mesh_file);
        if (!in)
          throw InputError("Grid/Mesh file = '" + mesh_file +
                           "' cannot be opened.");
        GridIn<dim> grid_in(triangulation);
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
            GridGenerator::generate_from_name_and_arguments(triangulation,
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
    triangulation.refine_global(n_refinements);
    if (scene_geometry.kind() == Geometry<dim>::Kind::axisymmetric)
      {
        double lowest = std::numeric_limits<double>::max(), size = 0.;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              {
                lowest = std::min(lowest, cell->vertex(v)[0]);
                size   = std::max(size, cell->diameter());
              }
        lowest = Utilities::MPI::min(lowest, get_communicator());
        size   = Utilities::MPI::max(size, get_communicator());
        if (lowest < -1e-12 * size)
          throw InputError("Grid/Geometry = axisymmetric: the grid reaches x "
                           "= " + std::to_string(lowest) +
                           ", a negative radius. An axisymmetric grid lies "
                           "in x >= 0 (x the radius, the axis at x = 0).");
      }
    update();
  }



  template <int dim>
  void
  Grid<dim>::refine_globally(const unsigned int n)
  {
    for (unsigned int k = 0; k < n; ++k)
      {
        before_change();
        triangulation.refine_global(1);
        update();
      }
  }



  template <int dim>
  void
  Grid<dim>::repartition(const CellWeight &weight)
  {
    // Connected only for this call: the refinements at the start balance
    // cells, as there are no points yet.
    const boost::signals2::scoped_connection weighting =
      triangulation.signals.weight.connect(weight);
    before_change();
    triangulation.repartition();
    update();
  }



  template <int dim>
  bool
  Grid<dim>::adapt(
    const std::function<
      int(const typename Triangulation<dim>::active_cell_iterator &)>
      &decide)
  {
    bool flagged = false;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->clear_refine_flag();
          cell->clear_coarsen_flag();
          const int decision = decide(cell);
          if (decision > 0)
            cell->set_refine_flag();
          else if (decision < 0 &&
                   cell->level() > static_cast<int>(n_refinements))
            cell->set_coarsen_flag();
        }
    // Drops the coarsening of families not all flagged, and whatever the
    // 2:1 balance forbids.
    triangulation.prepare_coarsening_and_refinement();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() &&
          (cell->refine_flag_set() || cell->coarsen_flag_set()))
        flagged = true;
    if (!Utilities::MPI::logical_or(flagged, get_communicator()))
      return false;

    before_change();
    triangulation.execute_coarsening_and_refinement();
    update();
    return true;
  }



  template <int dim>
  void
  Grid<dim>::update()
  {
    node_dof_handler.distribute_dofs(node_element);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(node_dof_handler, relevant);
    partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      node_dof_handler.locally_owned_dofs(),
      relevant,
      triangulation.get_communicator());
    hanging_nodes.clear();
    hanging_nodes.reinit(relevant);
    DoFTools::make_hanging_node_constraints(node_dof_handler, hanging_nodes);
    hanging_nodes.close();

    cells.assign(triangulation.n_active_cells(), CellGeometry());
    hanging_entries.clear();
    node_positions.assign(n_nodes(), Point<dim>());
    bool   cartesian = true;
    double min_edge  = std::numeric_limits<double>::max();
    for (const auto &cell : node_dof_handler.active_cell_iterators())
      {
        // Shape functions that reach beyond a point's cell reach the nodes
        // of ghost cells too.
        if (cell->is_ghost())
          for (unsigned int v = 0; v < n_vertices; ++v)
            node_positions[node_of_dof(cell->vertex_dof_index(v, 0))] =
              cell->vertex(v);
        if (!cell->is_locally_owned())
          continue;
        CellGeometry &data = cells[cell->active_cell_index()];
        for (unsigned int v = 0; v < n_vertices; ++v)
          {
            data.nodes[v] = node_of_dof(cell->vertex_dof_index(v, 0));
            node_positions[data.nodes[v]] = cell->vertex(v);
          }
        // The masters of a hanging vertex are vertices of the coarser
        // neighbour, an owned or ghost cell: their ids are known here.
        data.first_hanging = hanging_entries.size();
        for (unsigned int v = 0; v < n_vertices; ++v)
          if (const auto *masters = hanging_nodes.get_constraint_entries(
                cell->vertex_dof_index(v, 0)))
            for (const auto &[master, weight] : *masters)
              hanging_entries.push_back({v, node_of_dof(master), weight});
        data.n_hanging = hanging_entries.size() - data.first_hanging;

        // Axis-aligned box: vertex v = vertex 0 + sum over the set bits d of
        // v of h_d e_d.
        Tensor<1, dim> h;
        for (unsigned int d = 0; d < dim; ++d)
          h[d] = cell->vertex(1u << d)[d] - cell->vertex(0)[d];
        bool is_box = true;
        for (unsigned int v = 0; v < n_vertices; ++v)
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double expected =
                cell->vertex(0)[d] + ((v & (1u << d)) ? h[d] : 0.);
              if (std::abs(cell->vertex(v)[d] - expected) >
                  1e-12 * cell->diameter())
                is_box = false;
            }
        for (unsigned int d = 0; d < dim; ++d)
          if (!(h[d] > 0.))
            is_box = false;
        data.is_cartesian = is_box;
        if (is_box)
          for (unsigned int d = 0; d < dim; ++d)
            data.inverse_h[d] = 1. / h[d];
        cartesian = cartesian && is_box;
        min_edge  = std::min(min_edge, cell->minimum_vertex_distance());
      }

    const MPI_Comm comm = triangulation.get_communicator();
    all_cells_cartesian = Utilities::MPI::min(cartesian ? 1 : 0, comm) == 1;
    any_hanging = Utilities::MPI::logical_or(!hanging_entries.empty(), comm);
    min_cell_size       = Utilities::MPI::min(min_edge, comm);

    // Keep the mapping object when its kind stays: the particle handler
    // holds a reference to it.
    const bool mapping_is_cartesian =
      dynamic_cast<const MappingCartesian<dim> *>(mapping.get()) != nullptr;
    if (!mapping || mapping_is_cartesian != all_cells_cartesian)
      {
        if (all_cells_cartesian)
          mapping = std::make_unique<MappingCartesian<dim>>();
        else
          mapping = std::make_unique<MappingQ<dim>>(1);
      }

    changed();
  }



  template <int dim>
  types::boundary_id
  Grid<dim>::boundary_id(const std::string &name,
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



  template class Grid<2>;
  template class Grid<3>;
} // namespace mpm
