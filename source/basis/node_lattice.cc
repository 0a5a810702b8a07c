#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/basis/node_lattice.h>

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace mpm
{
  template <int dim>
  NodeLattice<dim>::NodeLattice(const Grid<dim> &grid, const std::string &entry)
    : grid(grid)
    , entry(entry)
  {
    build();
    grid_changed = grid.changed.connect([this]() { build(); });
  }



  template <int dim>
  void
  NodeLattice<dim>::build()
  {
    const MPI_Comm comm    = grid.get_communicator();
    const auto &   numbers = grid.node_numbering();
    const std::string needs =
      entry + " needs a grid of equal axis-aligned cells that fills a box "
              "(a subdivided_hyper_rectangle, refined or not): ";
    if (!grid.is_cartesian())
      throw InputError(needs + "this grid has cells that are not "
                               "axis-aligned boxes.");

    // Cell size and the box, over the cells this rank sees.
    Tensor<1, dim> smallest, largest;
    Point<dim>     lower, upper;
    for (unsigned int d = 0; d < dim; ++d)
      {
        smallest[d] = lower[d] = std::numeric_limits<double>::max();
        largest[d] = upper[d] = -std::numeric_limits<double>::max();
      }
    for (const auto &cell : numbers.active_cell_iterators())
      if (!cell->is_artificial())
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double h = cell->vertex(1u << d)[d] - cell->vertex(0)[d];
            smallest[d]    = std::min(smallest[d], h);
            largest[d]     = std::max(largest[d], h);
            lower[d]       = std::min(lower[d], cell->vertex(0)[d]);
            upper[d] = std::max(upper[d], cell->vertex(cell->n_vertices() - 1)[d]);
          }
    std::size_t n_lattice_cells = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        smallest[d] = Utilities::MPI::min(smallest[d], comm);
        largest[d]  = Utilities::MPI::max(largest[d], comm);
        lower[d]    = Utilities::MPI::min(lower[d], comm);
        upper[d]    = Utilities::MPI::max(upper[d], comm);
        if (largest[d] - smallest[d] > 1e-9 * largest[d])
          throw InputError(needs + "its cells are " + std::to_string(smallest[d]) +
                           " to " + std::to_string(largest[d]) +
                           " long along axis " + std::to_string(d) + ".");
        inverse_cell_size[d] = 1. / smallest[d];
        extent[d] = static_cast<int>(
          std::lround((upper[d] - lower[d]) * inverse_cell_size[d]));
        n_lattice_cells *= extent[d];
      }
    if (n_lattice_cells != grid.get_triangulation().n_global_active_cells())
      throw InputError(needs + "its " +
                       std::to_string(
                         grid.get_triangulation().n_global_active_cells()) +
                       " cells do not fill their bounding box.");

    const auto lattice_index = [&](const Point<dim> &x) {
      std::array<int, dim> index;
      for (unsigned int d = 0; d < dim; ++d)
        index[d] = static_cast<int>(
          std::lround((x[d] - lower[d]) * inverse_cell_size[d]));
      return index;
    };
    const auto key = [&](const std::array<int, dim> &index) {
      std::uint64_t k = 0;
      for (int d = dim - 1; d >= 0; --d)
        k = k * static_cast<std::uint64_t>(extent[d] + 1) + index[d];
      return k;
    };

    // Every node this rank sees: those of its owned and ghost cells.
    std::unordered_map<std::uint64_t, unsigned int> node_at;
    for (const auto &cell : numbers.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int v : cell->vertex_indices())
          node_at.emplace(key(lattice_index(cell->vertex(v))),
                          grid.node_of_dof(cell->vertex_dof_index(v, 0)));

    cells.assign(grid.get_triangulation().n_active_cells(), Cell());
    for (const auto &cell : numbers.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        Cell &data  = cells[cell->active_cell_index()];
        data.corner = lattice_index(cell->vertex(0));
        for (unsigned int k = 0; k < n_patch_nodes; ++k)
          {
            std::array<int, dim> index;
            bool                 inside = true;
            for (unsigned int d = 0, rest = k; d < dim; ++d, rest /= 4)
              {
                index[d] = data.corner[d] + static_cast<int>(rest % 4) - 1;
                inside   = inside && index[d] >= 0 && index[d] <= extent[d];
              }
            if (!inside)
              {
                data.nodes[k] = no_node;
                continue;
              }
            const auto found = node_at.find(key(index));
            // The cells around an owned cell are owned or ghost.
            AssertThrow(found != node_at.end(), ExcInternalError());
            data.nodes[k] = found->second;
          }
      }
  }



  template class NodeLattice<2>;
  template class NodeLattice<3>;
} // namespace mpm
