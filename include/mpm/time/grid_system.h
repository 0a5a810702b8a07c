#ifndef mpm_time_grid_system_h
#define mpm_time_grid_system_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/hp/fe_collection.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <mpm/base/input_error.h>
#include <mpm/basis/grid_basis.h>
#include <mpm/boundary/contact_active_set.h>
#include <mpm/boundary/nodal_condition.h>
#include <mpm/grid/grid.h>
#include <mpm/time/implicit_system.h>
#include <mpm/time/reached_nodes.h>

#include <set>


namespace mpm
{
  using namespace dealii;

  /**
   * The unknowns of implicit MPM on the background grid: FE_Q(1)^dim on
   * the cells that hold points (with shape functions that reach the cells
   * around, on every cell with a node that a point reaches, the others of
   * their nodes held at zero) and FE_Nothing elsewhere (hp), so the matrix
   * stays regular and its size follows the material; one point group per
   * cell, its supports from GridBasis spread over the nodes its points
   * reach; the grid conditions as
   * constraints, with the active set of the walls that hold the material
   * only while it presses, and the Coulomb force of those with friction
   * where the material slides on them.
   */
  template <int dim>
  class GridSystem : public ImplicitSystem<dim>
  {
  public:
    /**
     * `Newton/Integration`, the quadrature of full cells, and the weak
     * nodes' ties (ReachedNodes).
     */
    static void
    declare_parameters(ParameterHandler &prm);

    /** `conditions` act at the nodes, as constraints. */
    GridSystem(ParameterHandler &                              prm,
               MaterialPoints<dim> &                           points,
               const Grid<dim> &                               grid,
               const GridBasis<dim> &                          basis,
               const std::vector<const NodalCondition<dim> *> &conditions,
               ConditionalOStream &                            pcout);

    void
    setup(ImplicitState<dim> &state) override;

    bool
    has_active_set() const override
    {
      for (const NodalCondition<dim> *condition : conditions)
        if (condition->has_unilateral_nodes())
          return true;
      return false;
    }

    /**
     * Release, engage, and let held nodes of walls with friction start or
     * stop sliding (ContactActiveSet).
     */
    bool
    update_active_set(ImplicitState<dim> &state) override;

    /** The force of the material on each wall that holds a node. */
    void
    finish_step(const ImplicitState<dim> &state) override;

    void
    remember_active_set() override
    {
      contact.remember();
    }

    void
    restore_active_set() override
    {
      contact.restore();
    }

    /**
     * The contact nodes that hold the material, and those this rank visited
     * in the last step (a repartition carries those). They are numbered on
     * this rank, so a checkpoint is continued on as many ranks.
     */
    void
    save(boost::archive::binary_oarchive &archive) const override
    {
      archive << contact << pairs_in_step;
    }

    void
    load(boost::archive::binary_iarchive &archive) override
    {
      archive >> contact >> pairs_in_step;
      pairs_in_step_current = true;
    }

  private:
    /** The first dof of each node of a cell with unknowns, in `node_dof`. */
    void
    number_node_dofs();

    /**
     * Call f(cell, vertex, node) for each vertex of each locally owned
     * (and, if asked, ghost) cell with unknowns.
     */
    template <typename Function>
    void
    for_each_unknown_vertex(const Function &f, const bool with_ghosts) const;

    /**
     * One group per owned cell that holds points, in `group_cells`, with
     * its points and their supports (before the unknowns are numbered).
     */
    void
    collect_cell_groups(ImplicitState<dim> &state);

    /**
     * Each group's nodes (those its points reach, in the order met), dofs
     * and quadrature weight; every support spread over the group's nodes.
     */
    void
    number_cell_groups(ImplicitState<dim> &state) const;

    /**
     * Factor on the point volumes of a cell in the quadrature of the
     * internal force (see the Integration parameter).
     */
    double
    quadrature_scale(
      const typename DoFHandler<dim>::active_cell_iterator &cell) const;

    /**
     * Grid conditions on the nodes of active cells as constraints; contact
     * nodes only while engaged.
     */
    void
    make_constraints(ImplicitState<dim> &state);

    /**
     * Call f(cell, vertex, node, condition, first wall) for each vertex of
     * each locally owned (and, if asked, ghost) cell that holds points, for
     * each condition that acts on it; the condition's unilateral walls at
     * the node are numbered from `first wall` on.
     */
    template <typename Function>
    void
    for_each_constrained_vertex(const Function &f,
                                const bool      with_ghosts = false) const;

    /** A unilateral wall at a node. */
    struct ContactPair
    {
      unsigned int            node;
      unsigned int            wall;
      types::global_dof_index dof0;
      const Tensor<1, dim> &  outward;
      double                  friction;
      /**
       * Whether the node lies on another wall too: the force along one
       * wall is then the other's, so a held node sticks.
       */
      bool corner;
      /** The condition the wall belongs to, and its number there. */
      const NodalCondition<dim> &condition;
      unsigned int               k;
    };

    /** Call f(pair) once per unilateral wall of each node. */
    template <typename Function>
    void
    for_each_contact_node(const Function &f,
                          const bool      with_ghosts = false) const;

    /** Whether more than one wall acts on the node. */
    bool
    at_corner(const unsigned int node) const;

    /** The displacement of the node in the step, along the wall. */
    static Tensor<1, dim>
    sliding_increment(const ImplicitState<dim> &    state,
                      const types::global_dof_index dof0,
                      const Tensor<1, dim> &        outward);

    /** A unit vector as ContactActiveSet keeps it. */
    static std::array<double, 3>
    as_direction(const Tensor<1, dim> &unit);

    /**
     * Per contact node and wall (at its first dof plus the wall, ghosted):
     * nonzero where material
     * touches the wall, that is a point in an adjacent cell lies closer to
     * the wall than half its spacing. After a solve, at the points' new
     * positions and only for points that moved towards the wall.
     */
    TrilinosWrappers::MPI::Vector
    contact_gaps(const ImplicitState<dim> &state, const bool after_solve) const;

    const Grid<dim> &               grid;
    const GridBasis<dim> &          basis;
    const std::vector<const NodalCondition<dim> *> conditions;
    ConditionalOStream &            pcout;
    bool                            scale_full_cells;

    hp::FECollection<dim> fe_collection;
    DoFHandler<dim>       dof_handler;
    /** The nodes that smooth shape functions reach, and their ties. */
    ReachedNodes<dim> reached_nodes;
    /** The owned cell of each group. */
    std::vector<typename DoFHandler<dim>::active_cell_iterator> group_cells;

    /**
     * Whether the conditions must reach the nodes of ghost cells: shape
     * functions that reach beyond a point's cell assemble into them.
     */
    bool
    with_ghost_nodes() const
    {
      return supports_leave_cell();
    }

    /**
     * Whether a point's support may reach nodes that are not vertices of
     * its cell: smooth shape functions, or the linear ones on a grid with
     * hanging vertices (condensed onto the coarser face's nodes). The
     * unknowns then live on every cell with a reached node, and the nodes
     * of those cells that no point reaches (the hanging ones among them)
     * are held at zero.
     */
    bool
    supports_leave_cell() const
    {
      return basis.reaches_neighbours() || grid.has_hanging_nodes();
    }
    /** Per node id: the first of its dim dofs in this step. */
    std::vector<types::global_dof_index> node_dof;

    /**
     * The contact nodes (Grid node ids, stable while the grid does not
     * change; walls numbered as for_each_constrained_vertex does) that
     * hold the material, and how they slide. A step starts from the
     * previous step's set.
     */
    ContactActiveSet contact;
    /**
     * A repartitioned grid numbers its nodes anew and gives them to other
     * ranks: the contact set is carried by the nodes' coordinates.
     */
    std::vector<double>                contact_by_position;
    /** The (node, wall) pairs this rank visits in the current step. */
    std::set<std::pair<unsigned int, unsigned int>> pairs_in_step;
    /**
     * Whether pairs_in_step is numbered as the grid is now: not after a
     * change of the grid, until the next setup (an adaptive grid changes
     * several times between two steps).
     */
    bool pairs_in_step_current = true;
    boost::signals2::scoped_connection grid_changing, grid_changed;
  };



  // The walks over the system's vertices, shared by the constraints
  // (grid_system.cc) and the contact (grid_system_contact.cc).

  template <int dim>
  template <typename Function>
  void
  GridSystem<dim>::for_each_unknown_vertex(const Function &f,
                                           const bool      with_ghosts) const
  {
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!(cell->is_locally_owned() || (with_ghosts && cell->is_ghost())) ||
            cell->active_fe_index() != 0)
          continue;
        // Grid::node_of knows owned cells only; a ghost cell's nodes are
        // found through the node numbering (its relevant dofs).
        const typename DoFHandler<dim>::active_cell_iterator node_cell(
          &cell->get_triangulation(),
          cell->level(),
          cell->index(),
          &grid.node_numbering());
        for (const unsigned int v : cell->vertex_indices())
          f(cell,
            v,
            cell->is_locally_owned() ?
              grid.node_of(cell->active_cell_index(), v) :
              grid.node_of_dof(node_cell->vertex_dof_index(v, 0)));
      }
  }



  template <int dim>
  template <typename Function>
  void
  GridSystem<dim>::for_each_constrained_vertex(const Function &f,
                                               const bool with_ghosts) const
  {
    for_each_unknown_vertex(
      [&](const auto &cell, const unsigned int v, const unsigned int node) {
        // The unilateral walls of a node are numbered across the
        // conditions, in their order.
        unsigned int first_wall = 0;
        for (const NodalCondition<dim> *condition : conditions)
          if (condition->acts_on(node))
            {
              f(cell, v, node, *condition, first_wall);
              first_wall += condition->n_unilateral_walls(node);
            }
        if (first_wall > dim)
          throw RunError("Boundary conditions: a node of the grid lies "
                         "on more than " + std::to_string(dim) +
                         " walls that hold the material only while it "
                         "presses, which the implicit schemes cannot "
                         "hold.");
      },
      with_ghosts);
  }



  template <int dim>
  template <typename Function>
  void
  GridSystem<dim>::for_each_contact_node(const Function &f,
                                         const bool      with_ghosts) const
  {
    std::set<std::pair<unsigned int, unsigned int>> visited;
    for_each_constrained_vertex(
      [&](const auto &               cell,
          const unsigned int         v,
          const unsigned int         node,
          const NodalCondition<dim> &condition,
          const unsigned int         first_wall) {
        for (unsigned int k = 0; k < condition.n_unilateral_walls(node); ++k)
          if (visited.insert({node, first_wall + k}).second)
            f(ContactPair{node,
                          first_wall + k,
                          cell->vertex_dof_index(v, 0, 0),
                          condition.unilateral_normal(node, k),
                          condition.friction_coefficient(node, k),
                          at_corner(node),
                          condition,
                          k});
      },
      with_ghosts);
  }

} // namespace mpm

#endif
