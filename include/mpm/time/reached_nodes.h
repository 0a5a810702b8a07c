#ifndef mpm_time_reached_nodes_h
#define mpm_time_reached_nodes_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/basis/grid_basis.h>
#include <mpm/boundary/nodal_condition.h>
#include <mpm/grid/grid.h>
#include <mpm/time/implicit_state.h>

#include <array>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The grid nodes that smooth shape functions (GridBasis::
   * reaches_neighbours()) reach in an implicit step, with the volume of
   * material each carries (sum over points of N V), and the ties that hold
   * the weak ones: a node whose points weigh less than `Newton/Weak node
   * fraction` of a cell follows three strong nodes by linear
   * extrapolation (extended B-splines, after Yamaguchi, Moutsanidis and
   * Bazilevs 2021), so that Newton does not move it far on a sliver of
   * material.
   */
  template <int dim>
  class ReachedNodes
  {
  public:
    using CellIterator = typename DoFHandler<dim>::active_cell_iterator;

    /** `Newton/Weak node fraction`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /** Masters of ties never lie on a node that `conditions` act on. */
    ReachedNodes(ParameterHandler &                              prm,
                 const Grid<dim> &                               grid,
                 const GridBasis<dim> &                          basis,
                 const std::vector<const NodalCondition<dim> *> &conditions);

    /**
     * Flag the nodes that the groups' supports reach and sum what they
     * carry, over all ranks (ghosted). Group g holds the points of the
     * owned cell `cells[g]`.
     */
    void
    find(const std::vector<typename ImplicitState<dim>::PointGroup> &groups,
         const std::vector<CellIterator> &                          cells);

    /** Whether a point's support reaches the node (owned or ghost). */
    bool
    contains(const unsigned int node) const
    {
      return reached.local_element(node) != 0.;
    }

    /**
     * Tie each weak node near the cells of the last find() to strong
     * nodes, in `state.constraints` where no wall holds it and in
     * tie_constraints() on every component. Collective; all ranks choose
     * alike. `node_dof` gives the first dof of each node, of `n_dofs`.
     */
    void
    tie_weak_nodes(const std::vector<types::global_dof_index> &node_dof,
                   const types::global_dof_index               n_dofs,
                   const MPI_Comm                              comm,
                   ImplicitState<dim> &                        state);

    /** The dofs that tied nodes hang on, in this step (empty: no ties). */
    const IndexSet &
    tie_masters() const
    {
      return masters;
    }

    /** The ties of this step on every component, walls or not. */
    const AffineConstraints<double> &
    tie_constraints() const
    {
      return ties;
    }

  private:
    /** How strong a master the node makes; negative: none. */
    double
    strength(const unsigned int node) const;

    /**
     * Of two proposed ties (worth, direction code, masters' dofs), whether
     * the first is to be taken.
     */
    static bool
    better(const std::array<double, 5> &a, const std::array<double, 5> &b);

    const Grid<dim> &                              grid;
    const GridBasis<dim> &                         basis;
    const std::vector<const NodalCondition<dim> *> conditions;
    double                                         weak_fraction;

    /** Per node id: 1 where a point's support reaches it (ghosted). */
    LinearAlgebra::distributed::Vector<double> reached;
    /** Per node id: sum over points of N V, in the plane (ghosted). */
    LinearAlgebra::distributed::Vector<double> support_volume;
    /** The active cell indices of the owned cells that hold points. */
    std::vector<unsigned int> occupied_cells;
    IndexSet                  masters;
    AffineConstraints<double> ties;
  };
} // namespace mpm

#endif
