#include <deal.II/base/mpi.h>

#include <mpm/basis/grid_basis.h>

#include <limits>

namespace mpm
{
  template <int dim>
  void
  GridBasis<dim>::reinit(const GridNodes<dim> &nodes)
  {
    const DoFHandler<dim> &dof_handler = nodes.get_dof_handler();
    const auto &           tria        = dof_handler.get_triangulation();
    cells.assign(tria.n_active_cells(), CellData());
    bool   cartesian = true;
    double min_edge  = std::numeric_limits<double>::max();

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        CellData &data = cells[cell->active_cell_index()];
        for (unsigned int v = 0; v < n_vertices; ++v)
          {
            data.nodes[v]    = nodes.local_index(cell->vertex_dof_index(v, 0));
            data.vertices[v] = cell->vertex(v);
          }

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

    const MPI_Comm comm = tria.get_communicator();
    all_cells_cartesian = Utilities::MPI::min(cartesian ? 1 : 0, comm) == 1;
    min_cell_size       = Utilities::MPI::min(min_edge, comm);
  }



  template class GridBasis<2>;
  template class GridBasis<3>;
} // namespace mpm
