#ifndef mpm_grid_grid_h
#define mpm_grid_grid_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/affine_constraints.h>

#include <boost/signals2/signal.hpp>

#include <mpm/grid/geometry.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The background grid of a scene and the identity of its nodes.
   *
   * The grid is described in the prm file: one of deal.II's GridGenerator
   * functions by name and arguments, or a gmsh file; boundary ids get names,
   * which the boundary conditions use. It lives on a
   * parallel::distributed::Triangulation (p4est).
   *
   * A node is a vertex of the grid. Nodes are numbered by a scalar Q1
   * DoFHandler: a node id is the rank-local index of its degree of freedom
   * (the locally owned nodes first, then the ghost nodes of the ghost
   * cells), the same for every basis, condition and nodal storage. What is
   * stored per node, and where, is the business of the storage, which turns
   * ids into offsets.
   *
   * The geometry of each locally owned cell (its node ids, vertices and, on
   * an axis-aligned box, its inverse edge lengths) is cached here once, for
   * the Q1 basis and anyone else who asks "which nodes does this cell
   * have".
   *
   * Whatever changes the grid (a refinement, a moved vertex) goes through
   * this class, which numbers the nodes again and then fires `changed`, so
   * that everything keyed by node ids can rebuild.
   */
  template <int dim>
  class Grid
  {
  public:
    static constexpr unsigned int n_vertices = 1u << dim;

    static void
    declare_parameters(ParameterHandler &prm);

    /** Parse the `Grid` subsection (the handler is at top level). */
    Grid(ParameterHandler &prm, const MPI_Comm communicator);

    /**
     * Build the coarse grid, refine it, choose the mapping and number the
     * nodes. Bad input (a missing mesh file, a generator that fails)
     * throws InputError.
     */
    void
    create();

    /**
     * Refine every cell `n` times: fire `before_change`, refine, number the
     * nodes and fire `changed`.
     */
    void
    refine_globally(const unsigned int n);

    /**
     * The extra cost of a cell in a repartition (deal.II's `weight` signal,
     * summed over the cell's children or parent as that signal documents).
     */
    using CellWeight = std::function<unsigned int(
      const typename Triangulation<dim>::cell_iterator &,
      const typename Triangulation<dim>::CellStatus)>;

    /**
     * Give the ranks new shares of the cells, balanced by `weight`: fire
     * `before_change`, let p4est repartition, number the nodes and fire
     * `changed`. The cells stay the same.
     */
    void
    repartition(const CellWeight &weight);

    /**
     * Refine and coarsen the locally owned cells as `decide` says (+1
     * refine, -1 coarsen, 0 keep; never coarser than the grid of the
     * scene, base_level()), balanced 2:1 by p4est, and split evenly among
     * the ranks. If the flags change nothing, the grid is left alone and
     * false returned; otherwise fire `before_change`, change the cells,
     * number the nodes, fire `changed` and return true (p4est may still
     * refuse a coarsening that the flags allow, for its 2:1 balance; the
     * cells are then split anew all the same).
     */
    bool
    adapt(const std::function<int(
            const typename Triangulation<dim>::active_cell_iterator &)>
            &decide);

    /** The level of the cells of the scene's grid (Global refinements). */
    unsigned int
    base_level() const
    {
      return n_refinements;
    }

    /**
     * Move every vertex x to transformation(x); then number the nodes and
     * fire `changed`. The mapping is chosen again, so this must happen
     * before MaterialPoints are built on the grid (they keep the mapping).
     */
    template <typename Transformation>
    void
    transform(const Transformation &transformation)
    {
      GridTools::transform(transformation, triangulation);
      update();
    }

    /**
     * Fired before the cells change (refinement), while the old cells
     * still exist: the points save what they need to be carried across.
     */
    mutable boost::signals2::signal<void()> before_change;

    /**
     * Fired after the grid changed and its nodes were numbered again: node
     * ids and cell geometry are those of the new grid. Whatever is keyed by
     * node ids or cells rebuilds here; the points, connected at the front,
     * are in their new cells first.
     */
    mutable boost::signals2::signal<void()> changed;

    /**
     * The boundary id of a named boundary; `entry` names the parameter that
     * used the name, for the message if it is unknown.
     */
    types::boundary_id
    boundary_id(const std::string &name, const std::string &entry) const;

    const parallel::distributed::Triangulation<dim> &
    get_triangulation() const
    {
      return triangulation;
    }

    MPI_Comm
    get_communicator() const
    {
      return triangulation.get_communicator();
    }

    /**
     * MappingCartesian when every cell is an axis-aligned box (fast point
     * location), MappingQ(1) otherwise (gmsh grids).
     */
    const Mapping<dim> &
    get_mapping() const
    {
      return *mapping;
    }

    /** What the plane of a 2D scene stands for, and its measures. */
    const Geometry<dim> &
    geometry() const
    {
      return scene_geometry;
    }

    /** True if every cell of the grid is an axis-aligned box. */
    bool
    is_cartesian() const
    {
      return all_cells_cartesian;
    }

    /**
     * Smallest edge of any cell, over all ranks: the length that limits the
     * time step and the distance a point may move in one.
     */
    double
    minimum_cell_size() const
    {
      return min_cell_size;
    }

    /** The scalar Q1 numbering of the nodes. */
    const DoFHandler<dim> &
    node_numbering() const
    {
      return node_dof_handler;
    }

    /** Owned and ghost nodes of this rank, for distributed nodal storage. */
    const std::shared_ptr<const Utilities::MPI::Partitioner> &
    node_partitioner() const
    {
      return partitioner;
    }

    /** Node ids on this rank run from 0 to n_nodes(): owned, then ghost. */
    unsigned int
    n_nodes() const
    {
      return partitioner->locally_owned_size() + partitioner->n_ghost_indices();
    }

    /** The node id of a global index of node_numbering(). */
    unsigned int
    node_of_dof(const types::global_dof_index global_index) const
    {
      return partitioner->global_to_local(global_index);
    }

    /** The position of a node of a locally owned or ghost cell. */
    const Point<dim> &
    node_position(const unsigned int node) const
    {
      return node_positions[node];
    }

    /**
     * The outward normal of face f of a cell, as long as the face is large
     * (its length in 2D, the area of the parallelogram of its first two
     * edges in 3D), so that sums over faces weigh them by size.
     */
    template <class CellIterator>
    static Tensor<1, dim>
    face_normal(const CellIterator &cell, const unsigned int f)
    {
      const auto     face = cell->face(f);
      Tensor<1, dim> normal;
      if constexpr (dim == 2)
        normal = cross_product_2d(face->vertex(1) - face->vertex(0));
      else
        normal = cross_product_3d(face->vertex(1) - face->vertex(0),
                                  face->vertex(2) - face->vertex(0));
      if (normal * (face->center() - cell->center()) < 0.)
        normal = -normal;
      return normal;
    }

    /** The node id of vertex v of a locally owned cell. */
    unsigned int
    node_of(const unsigned int active_cell_index, const unsigned int v) const
    {
      return cells[active_cell_index].nodes[v];
    }

    /**
     * Constraints of the nodes that hang on the faces of coarser cells, as
     * a scalar field on node_numbering() (empty on a uniform grid).
     */
    const AffineConstraints<double> &
    hanging_node_constraints() const
    {
      return hanging_nodes;
    }

    /**
     * What the Q1 basis needs of a locally owned cell. The vertices are
     * those of its nodes, node_position(nodes[v]): they are not held twice.
     */
    struct CellGeometry
    {
      std::array<unsigned int, n_vertices> nodes;
      /** 1 / edge length per direction; set on axis-aligned boxes only. */
      Tensor<1, dim> inverse_h;
      bool           is_cartesian = false;
      /** The cell's entries in hanging_vertices(): first and how many. */
      unsigned int first_hanging = 0;
      unsigned int n_hanging     = 0;
    };

    /**
     * A vertex of a cell that hangs on the face (or edge) of a coarser
     * neighbour: its value is the weighted sum of those of its master
     * nodes, one entry per master.
     */
    struct HangingVertex
    {
      unsigned int vertex;
      unsigned int master;
      double       weight;
    };

    /** Whether any cell, on any rank, has a hanging vertex. */
    bool
    has_hanging_nodes() const
    {
      return any_hanging;
    }

    /** The hanging vertices of a locally owned cell (none on a uniform grid). */
    ArrayView<const HangingVertex>
    hanging_vertices(const CellGeometry &cell) const
    {
      return {hanging_entries.data() + cell.first_hanging, cell.n_hanging};
    }

    const CellGeometry &
    cell_geometry(const unsigned int active_cell_index) const
    {
      return cells[active_cell_index];
    }

  private:
    /** Number the nodes, cache the cells, choose the mapping. */
    void
    update();

    std::string                               generator;
    std::string                               arguments;
    std::string                               mesh_file;
    unsigned int                              n_refinements;
    std::map<std::string, types::boundary_id> boundary_names;
    const Geometry<dim>                       scene_geometry;

    parallel::distributed::Triangulation<dim> triangulation;
    std::unique_ptr<Mapping<dim>>             mapping;
    FE_Q<dim>                                 node_element;
    DoFHandler<dim>                           node_dof_handler;
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
    AffineConstraints<double>                          hanging_nodes;

    /** By node id; set for the nodes of locally owned and ghost cells. */
    std::vector<Point<dim>> node_positions;
    /** Indexed by active cell index; only locally owned entries are set. */
    std::vector<CellGeometry> cells;
    /** The hanging vertices of all owned cells, cell after cell. */
    std::vector<HangingVertex> hanging_entries;
    bool                       any_hanging = false;
    bool                      all_cells_cartesian = true;
    double                    min_cell_size       = 0.;
  };
} // namespace mpm

#endif
