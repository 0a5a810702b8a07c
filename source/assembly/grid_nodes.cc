#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>

#include <mpm/assembly/grid_nodes.h>

namespace mpm
{
  template <int dim>
  GridNodes<dim>::GridNodes(
    const parallel::distributed::Triangulation<dim> &tria)
    : triangulation(tria)
    , fe(FE_Q<dim>(1), NodalLayout::n_components)
    , dof_handler(tria)
  {}



  template <int dim>
  void
  GridNodes<dim>::setup()
  {
    dof_handler.distribute_dofs(fe);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      dof_handler.locally_owned_dofs(),
      relevant,
      triangulation.get_communicator());
    values.reinit(partitioner);

    const unsigned int n_local = partitioner->locally_owned_size() +
                                 partitioner->n_ghost_indices();
    // A node's values must be consecutive and start at a multiple of
    // n_components in the local numbering (the active flags rely on it).
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int v : cell->vertex_indices())
          for (unsigned int c = 0; c < NodalLayout::n_components; ++c)
            AssertThrow(local_index(cell->vertex_dof_index(v, c)) ==
                          local_index(cell->vertex_dof_index(v, 0)) + c &&
                        local_index(cell->vertex_dof_index(v, 0)) %
                            NodalLayout::n_components ==
                          0,
                        ExcInternalError());
    active_flag.assign(n_local / NodalLayout::n_components, false);
    active_nodes.clear();

    imported_nodes.clear();
    for (const auto &range : partitioner->import_indices())
      for (unsigned int i = range.first; i < range.second; ++i)
        if (i % NodalLayout::n_components == 0)
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
    double *v = values.get_values();
    for (const unsigned int node : active_nodes)
      for (unsigned int c = first_component; c < first_component + n_components;
           ++c)
        v[node + c] = 0.;
    for (const unsigned int node : imported_nodes)
      for (unsigned int c = first_component; c < first_component + n_components;
           ++c)
        v[node + c] = 0.;

    full_projection = (n_components == NodalLayout::n_components);
    if (full_projection)
      {
        for (const unsigned int node : active_nodes)
          active_flag[node / NodalLayout::n_components] = false;
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
    const double *v = values.get_values();
    for (const unsigned int node : imported_nodes)
      if (!active_flag[node / NodalLayout::n_components] &&
          v[node + NodalLayout::mass] > 0.)
        solve_nodes.push_back(node);
  }



  template class GridNodes<2>;
  template class GridNodes<3>;
} // namespace mpm
