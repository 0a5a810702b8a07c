#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>

#include <mpm/assembly/grid_nodes.h>

#include <algorithm>

namespace mpm
{
  template <int dim>
  GridNodes<dim>::GridNodes(const Grid<dim> &grid)
    : grid(grid)
    , system_element(FE_Q<dim>(1), NodalLayout::n_components)
    , system_dof_handler(grid.get_triangulation())
  {
    grid_changed = grid.changed.connect([this]() { setup(); });
  }



  template <int dim>
  void
  GridNodes<dim>::setup()
  {
    system_dof_handler.distribute_dofs(system_element);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(system_dof_handler, relevant);
    values.reinit(system_dof_handler.locally_owned_dofs(),
                  relevant,
                  grid.get_communicator());

    // Value c of node i sits at n_components i + c: the system numbering
    // must be the grid's node numbering, component by component.
    for (const auto &cell : grid.node_numbering().active_cell_iterators())
      if (!cell->is_artificial())
        {
          const typename DoFHandler<dim>::active_cell_iterator system_cell(
            &grid.get_triangulation(),
            cell->level(),
            cell->index(),
            &system_dof_handler);
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int c = 0; c < NodalLayout::n_components; ++c)
              AssertThrow(
                system_cell->vertex_dof_index(v, c) ==
                    NodalLayout::n_components * cell->vertex_dof_index(v, 0) +
                      c &&
                  values.get_partitioner()->global_to_local(
                    system_cell->vertex_dof_index(v, c)) ==
                    NodalLayout::n_components *
                        grid.node_of_dof(cell->vertex_dof_index(v, 0)) +
                      c,
                ExcInternalError());
        }

    active_flag.assign(grid.n_nodes(), false);
    active_nodes.clear();
    solve_nodes.clear();

    imported_nodes.clear();
    for (const auto &range : grid.node_partitioner()->import_indices())
      for (unsigned int i = range.first; i < range.second; ++i)
        imported_nodes.push_back(i);
    std::sort(imported_nodes.begin(), imported_nodes.end());
    imported_nodes.erase(std::unique(imported_nodes.begin(),
                                     imported_nodes.end()),
                         imported_nodes.end());
  }



  template <int dim>
  void
  GridNodes<dim>::begin_projection(const unsigned int first_component,
                                   const unsigned int n_components)
  {
    values.zero_out_ghost_values();
    for (const unsigned int node : active_nodes)
      {
        double *v = values_of(node);
        for (unsigned int c = first_component;
             c < first_component + n_components;
             ++c)
          v[c] = 0.;
      }
    for (const unsigned int node : imported_nodes)
      {
        double *v = values_of(node);
        for (unsigned int c = first_component;
             c < first_component + n_components;
             ++c)
          v[c] = 0.;
      }

    full_projection = (n_components == NodalLayout::n_components);
    if (full_projection)
      {
        for (const unsigned int node : active_nodes)
          active_flag[node] = false;
        active_nodes.clear();
      }
  }



  template <int dim>
  void
  GridNodes<dim>::finish_projection()
  {
    values.compress(VectorOperation::add);
    values.update_ghost_values();

    // A partial projection fills the same nodes as the full one before it.
    if (!full_projection)
      return;
    solve_nodes = active_nodes;
    for (const unsigned int node : imported_nodes)
      if (!active_flag[node] && values_of(node)[NodalLayout::mass] > 0.)
        solve_nodes.push_back(node);
  }



  template <int dim>
  const LinearAlgebra::distributed::Vector<double> &
  GridNodes<dim>::output_vector() const
  {
    values.update_ghost_values();
    // No point reaches a hanging vertex, so the projection leaves it
    // empty; no step reads what is written here.
    for (const auto &cell : grid.get_triangulation().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto &geometry = grid.cell_geometry(cell->active_cell_index());
          if (geometry.n_hanging == 0)
            continue;
          for (const auto &entry : grid.hanging_vertices(geometry))
            std::fill_n(values.get_values() + NodalLayout::n_components *
                                                geometry.nodes[entry.vertex],
                        NodalLayout::n_components,
                        0.);
          for (const auto &entry : grid.hanging_vertices(geometry))
            {
              double *hanging = values.get_values() +
                                NodalLayout::n_components *
                                  geometry.nodes[entry.vertex];
              const double *master = values_of(entry.master);
              for (unsigned int c = 0; c < NodalLayout::n_components; ++c)
                hanging[c] += entry.weight * master[c];
            }
        }
    return values;
  }



  template class GridNodes<2>;
  template class GridNodes<3>;
} // namespace mpm
