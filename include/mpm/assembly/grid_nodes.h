#ifndef mpm_assembly_grid_nodes_h
#define mpm_assembly_grid_nodes_h

#include <deal.II/base/partitioner.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/grid/grid.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The nodal values of the explicit scheme on the background grid: one
   * vector, distributed with the grid, that holds per node the lumped mass,
   * the velocity (momentum while it is being accumulated) and the force
   * (acceleration after the nodal solve), interleaved so a node's values
   * sit together in memory. Nodes are the Grid's node ids; the values of
   * node i start at values_of(i).
   *
   * Only nodes that carry material are touched: the set of active nodes is
   * recorded while projecting and only those (plus the few nodes shared with
   * other ranks) are cleared before the next projection. An empty region of
   * the grid therefore costs nothing per step.
   */
  template <int dim>
  class GridNodes
  {
  public:
    struct NodalLayout
    {
      static constexpr unsigned int mass         = 0;
      static constexpr unsigned int velocity     = 1;
      static constexpr unsigned int force        = 1 + dim;
      static constexpr unsigned int n_components = 1 + 2 * dim;
    };

    /** Connects to Grid::changed, which calls setup() again. */
    explicit GridNodes(const Grid<dim> &grid);

    /** Size the storage for the grid's nodes. */
    void
    setup();

    /** The values of a node, NodalLayout::n_components of them. */
    double *
    values_of(const unsigned int node)
    {
      return values.get_values() + node * NodalLayout::n_components;
    }

    const double *
    values_of(const unsigned int node) const
    {
      return values.get_values() + node * NodalLayout::n_components;
    }

    /**
     * Start a projection: clear the given range of components on every node
     * that may hold a value from the last one. Nodes then written by the
     * projection must be reported with mark_active().
     */
    void
    begin_projection(const unsigned int first_component,
                     const unsigned int n_components);

    void
    mark_active(const unsigned int node)
    {
      if (!active_flag[node])
        {
          active_flag[node] = true;
          active_nodes.push_back(node);
        }
    }

    /**
     * Sum the contributions across ranks, so that every active node, owned
     * or ghost, holds the full sum.
     */
    void
    finish_projection();

    /** Nodes this rank works on: its active nodes and its imported ones. */
    const std::vector<unsigned int> &
    nodes_to_solve() const
    {
      return solve_nodes;
    }

    /**
     * The values as a vector of the FESystem of 1 + 2 dim Q1 components on
     * output_dof_handler(), for the grid output (DataOut). Ghost values are
     * brought up to date first, and the vertices that hang on a coarser
     * cell's face get the values that the nodes of that face give them.
     */
    const LinearAlgebra::distributed::Vector<double> &
    output_vector() const;

    /**
     * The FESystem numbering of the nodes, distributed on the first call
     * after each setup(): only the grid output needs it.
     */
    const DoFHandler<dim> &
    output_dof_handler() const;

  private:
    const Grid<dim> &grid;
    FESystem<dim>    system_element;
    /**
     * output_dof_handler(): its dof (node, c) is the value c of the node's
     * global index g in the grid's node numbering, n_components g + c
     * (checked when it is built): deal.II numbers a vertex's components
     * together, vertices in the order of the scalar numbering.
     */
    mutable std::unique_ptr<DoFHandler<dim>>           system_dof_handler;
    mutable LinearAlgebra::distributed::Vector<double> values;

    /** Per node: written by the current projection. */
    std::vector<bool>         active_flag;
    std::vector<unsigned int> active_nodes;
    /** Owned nodes that other ranks may add to in compress(). */
    std::vector<unsigned int> imported_nodes;
    std::vector<unsigned int> solve_nodes;
    bool                      full_projection = true;

    boost::signals2::scoped_connection grid_changed;
  };
} // namespace mpm

#endif
