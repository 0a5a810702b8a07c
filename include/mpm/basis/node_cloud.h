#ifndef mpm_basis_node_cloud_h
#define mpm_basis_node_cloud_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <boost/serialization/vector.hpp>

#include <mpm/boundary/contact_active_set.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>
#include <mpm/points/material_points.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The nodes of the Galerkin meshfree method (Iaconeta et al. 2017,
   * Algorithm 2). They start at the background grid vertices of the cells
   * that hold material, each with the grid condition of its vertex, and
   * from then on move with the solution and keep their velocity and
   * acceleration from step to step, as finite element nodes do; the grid
   * is only the frame that holds the points.
   *
   * The grid's walls hold nodes where the material reaches them (see
   * Wall): the cloud is not tied to the grid, so a node that did not
   * start on a wall can come to one.
   *
   * On several ranks every rank holds the whole cloud, numbered by
   * position: the nodes are about one per cell of material, few against
   * the points, whose supports, assembly and unknowns the ranks split
   * (CloudSystem). A support then never needs a node another rank has.
   */
  template <int dim>
  class NodeCloud
  {
  public:
    using Condition = typename DirichletConditions<dim>::Constraint;

    NodeCloud(const MaterialPoints<dim> &      points,
              const Grid<dim> &                grid,
              const DirichletConditions<dim> & dirichlet);

    unsigned int
    size() const
    {
      return positions.size();
    }

    /** The grid's smallest cell edge: the nodal spacing h. */
    double
    spacing() const
    {
      return nodal_spacing;
    }

    /**
     * The components of node i that a wall holds: those of the wall it
     * started on (all on a fixed wall, the normal one on a slip wall) and
     * those of the wall it was brought to (see Wall).
     */
    std::array<bool, dim>
    held_components(const unsigned int i) const;

    /**
     * A wall of the grid, the plane outward . x = offset, along an axis.
     * Nodes that do not start on it are held there once the material
     * reaches it (CloudSystem's active set): all components on fixed
     * and contact walls, the normal one on slip walls; only contact walls
     * let go again.
     */
    struct Wall
    {
      Tensor<1, dim> outward;
      double         offset;
      unsigned int   axis;
      typename DirichletConditions<dim>::WallKind kind;
    };

    std::vector<Point<dim>>     positions;
    std::vector<Tensor<1, dim>> velocities;
    std::vector<Tensor<1, dim>> accelerations;
    /** The grid condition of each node's starting vertex (no normals: none). */
    std::vector<Condition> conditions;
    /** False until the nodes have taken v and a from the points. */
    bool has_history = false;

    std::vector<Wall> walls;
    /**
     * The (node, wall) pairs that the material has brought to a wall, by
     * the index of the wall in `walls`. Kept from step to step.
     */
    ContactActiveSet held_by_walls;

    bool
    is_held_by(const unsigned int i, const unsigned int w) const
    {
      return held_by_walls.holds(i, w);
    }

    /**
     * The state that moves with the run, for Checkpoint. The walls and the
     * nodes' conditions come from the scene and the starting grid, which a
     * restarted run builds again in the same order.
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &positions &velocities &accelerations &held_by_walls
        &has_history;
    }

  private:
    /** The entries of one node in the exchange between ranks. */
    static constexpr unsigned int node_record_size = 2 + 2 * dim + dim * dim;

    static void
    pack_node(const Point<dim> &   x,
              const Condition &    condition,
              std::vector<double> &record);

    static void
    unpack_node(const double *record, Point<dim> &x, Condition &condition);

    /**
     * The wall of a boundary face (its outward direction from the cell's
     * centre, and its centre), unless a wall of the same plane is known.
     */
    void
    add_wall(const Tensor<1, dim> &                            outward,
             const Point<dim> &                                face_center,
             const typename DirichletConditions<dim>::WallKind kind);

    /** Orders points by x, then y, then z: the nodes' order on several ranks. */
    struct LexicographicLess
    {
      bool
      operator()(const Point<dim> &a, const Point<dim> &b) const
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (a[d] != b[d])
            return a[d] < b[d];
        return false;
      }
    };

    double nodal_spacing;
  };
} // namespace mpm

#endif
