#ifndef mpm_assembly_grid_nodes_h
#define mpm_assembly_grid_nodes_h

#include <deal.II/base/partitioner.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The nodal values of the background grid: one vector, distributed with
   * the grid, that holds per node the lumped mass, the velocity (momentum
   * while it is being accumulated) and the force (acceleration after the
   * nodal solve), interleaved so a node's values sit together in memory.
   * deal.II provides the numbering through a DoFHandler with an
   * FESystem of 1 + 2 dim Q1 components, which also makes the grid output a
   * plain DataOut.
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

    explicit GridNodes(const parallel::distributed::Triangulation<dim> &tria);

    /** Number the nodes and size the vector; call after the grid exists. */
    void
    setup();

    const DoFHandler<dim> &
    get_dof_handler() const
    {
      return dof_handler;
    }

    /** Local index (into data()) of the first value of a global dof. */
    unsigned int
    local_index(const types::global_dof_index global_dof) const
    {
      return partitioner->global_to_local(global_dof);
    }

    double *
    data()
    {
      return values.get_values();
    }

    const double *
    data() const
    {
      return values.get_values();
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
      if (!active_flag[node / NodalLayout::n_components])
        {
          active_flag[node / NodalLayout::n_components] = true;
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

    const LinearAlgebra::distributed::Vector<double> &
    vector() const
    {
      return values;
    }

  private:
    const parallel::distributed::Triangulation<dim> &triangulation;
    FESystem<dim>                                    fe;
    DoFHandler<dim>                                  dof_handler;
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
    LinearAlgebra::distributed::Vector<double>         values;

    /** Per node (index / n_components): written by the current projection. */
    std::vector<bool>         active_flag;
    std::vector<unsigned int> active_nodes;
    /** Owned nodes that other ranks may add to in compress(). */
    std::vector<unsigned int> imported_nodes;
    std::vector<unsigned int> solve_nodes;
    bool                      full_projection = true;
  };
} // namespace mpm

#endif
