#ifndef mpm_basis_node_lattice_h
#define mpm_basis_node_lattice_h

#include <deal.II/base/tensor.h>
#include <deal.II/base/utilities.h>

#include <mpm/grid/grid.h>

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The background grid seen as a lattice of nodes, for shape functions that
   * reach beyond a point's cell (GIMP and B-splines): each locally owned
   * cell knows its lattice index and the node ids of the 4^dim nodes from
   * one below its lower corner to two above it, which are the nodes of the
   * 3^dim cells around it (owned or ghost, so every rank that owns the cell
   * has them). A lattice node outside the grid has no id.
   *
   * This needs a grid of equal axis-aligned cells that fills a box (a
   * subdivided_hyper_rectangle, refined or not); any other grid is refused
   * with a message that names `entry`, the parameter that asked for the
   * lattice. The lattice is built again when the grid changes.
   */
  template <int dim>
  class NodeLattice
  {
  public:
    /** Lattice nodes per direction around a cell: one below, two above. */
    static constexpr unsigned int patch_width   = 4;
    static constexpr unsigned int n_patch_nodes = Utilities::pow(4, dim);
    static constexpr unsigned int no_node =
      std::numeric_limits<unsigned int>::max();

    struct Cell
    {
      /** Lattice index of the cell's lower corner, per direction. */
      std::array<int, dim> corner;
      /**
       * Node ids of the lattice nodes corner + k - 1, k in 0..3 per
       * direction, at sum_d k_d 4^d; no_node outside the grid.
       */
      std::array<unsigned int, n_patch_nodes> nodes;
    };

    NodeLattice(const Grid<dim> &grid, const std::string &entry);

    const Cell &
    cell(const unsigned int active_cell_index) const
    {
      return cells[active_cell_index];
    }

    /** Cells of the grid along direction d. */
    int
    n_cells(const unsigned int d) const
    {
      return extent[d];
    }

    /** 1 / cell edge per direction. */
    const Tensor<1, dim> &
    inverse_h() const
    {
      return inverse_cell_size;
    }

  private:
    /** Check the grid and index its cells and nodes. */
    void
    build();

    const Grid<dim> &    grid;
    const std::string    entry;
    std::array<int, dim> extent;
    Tensor<1, dim>       inverse_cell_size;
    /** Indexed by active cell index; only locally owned entries are set. */
    std::vector<Cell> cells;

    boost::signals2::scoped_connection grid_changed;
  };
} // namespace mpm

#endif
