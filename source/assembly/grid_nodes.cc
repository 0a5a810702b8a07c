#include <deal.II/fe/fe_q.h>

#include <mpm/assembly/grid_nodes.h>

#include <algorithm>

namespace mpm
{
  template <int dim>
  GridNodes<dim>::GridNodes(const Grid<dim> &grid)
    : grid(grid)
    , system_element(FE_Q<dim>(1), NodalLayout::n_components)
  {
    grid_changed = grid.changed.connect([this]() { setup(); });
  }



  template <int dim>
  void
  GridNodes<dim>::setup()
  {
    // Value c of node i sits at n_components i + c: the grid's node
    // partition with each index widened to its components keeps the nodes'
    // order, owned and ghost. A DoFHandler of the FESystem would number
    // them so too, and cost as much memory as the points' positions.
    constexpr unsigned int n = NodalLayout::n_components;
    const Utilities::MPI::Partitioner &nodes = *grid.node_partitioner();
    IndexSet owned(n * nodes.size()), ghosts(n * nodes.size());
    for (auto range = nodes.locally_owned_range().begin_intervals();
         range != nodes.locally_owned_range().end_intervals();
         ++range)
      owned.add_range(n * *range->begin(), n * (range->last() + 1));
    std::vector<types::global_dof_index> ghost_values;
    ghost_values.reserve(n * nodes.n_ghost_indices());
    for (const auto g : nodes.ghost_indices())
      for (unsigned int c = 0; c < n; ++c)
        ghost_values.push_back(n * g + c);
    ghosts.add_indices(ghost_values.begin(), ghost_values.end());
    values.reinit(owned, ghosts, grid.get_communicator());
    system_dof_handler.reset();

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
  const DoFHandler<dim> &
  GridNodes<dim>::output_dof_handler() const
  {
    if (system_dof_handler)
      return *system_dof_handler;
    system_dof_handler =
      std::make_unique<DoFHandler<dim>>(grid.get_triangulation());
    system_dof_handler->distribute_dofs(system_element);
    for (const auto &cell : grid.node_numbering().active_cell_iterators())
      if (!cell->is_artificial())
        {
          const typename DoFHandler<dim>::active_cell_iterator system_cell(
            &grid.get_triangulation(),
            cell->level(),
            cell->index(),
            system_dof_handler.get());
          for (const unsigned int v : cell->vertex_indices())
            for (unsigned int c = 0; c < NodalLayout::n_components; ++c)
              AssertThrow(system_cell->vertex_dof_index(v, c) ==
                            NodalLayout::n_components *
                                cell->vertex_dof_index(v, 0) +
                              c,
                          ExcInternalError());
        }
    return *system_dof_handler;
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
