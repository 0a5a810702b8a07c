#ifndef mpm_boundary_boundary_walls_h
#define mpm_boundary_boundary_walls_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <mpm/grid/grid.h>

#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The grid's boundary seen as walls, one per boundary id: the one
   * description of walls that the fixed, slip and contact walls
   * (DirichletConditions) and the friction walls (FrictionWalls) hold their
   * nodes by. For each node on a wall: the wall's outward normal there,
   * the sum of the normals of its faces at the node weighted by their size
   * (a curved wall averages them), the node's share of the wall's area,
   * int N dA over its faces (in axisymmetry over the surface of revolution,
   * in plane stress over the plate's initial thickness), and its position.
   * Walls are found on the boundary faces of every cell this rank sees
   * (owned and ghost), so a rank knows the walls of every node of its
   * cells. for_each_boundary_face() is the one walk over the grid's
   * boundary faces, which the axis check and the meshfree cloud use too.
   */
  template <int dim>
  class BoundaryWalls
  {
  public:
    /** One wall at one node. */
    struct NodeOnWall
    {
      unsigned int node;
      /** The wall's index in the ids the walls were built from. */
      unsigned int wall;
      /** The size-weighted sum of the wall's face normals at the node. */
      Tensor<1, dim> normal;
      double         share = 0.;
      Point<dim>     position;
    };

    /**
     * Call f(cell, f) for every boundary face f of the cells this rank
     * sees (owned and ghost), or of its owned cells only, in the order of
     * the cells.
     */
    template <typename Function>
    static void
    for_each_boundary_face(const Grid<dim> &grid,
                           const bool       owned_only,
                           const Function & f)
    {
      for (const auto &cell : grid.node_numbering().active_cell_iterators())
        {
          if (cell->is_artificial() || (owned_only && !cell->is_locally_owned()))
            continue;
          for (const unsigned int face : cell->face_indices())
            if (cell->at_boundary(face))
              f(cell, face);
        }
    }

    /** The walls whose boundary ids are `ids`, one wall per entry. */
    BoundaryWalls(const Grid<dim> &                      grid,
                  const std::vector<types::boundary_id> &ids);

    /** Every wall at every node, ordered by node, then by wall. */
    const std::vector<NodeOnWall> &
    nodes_on_walls() const
    {
      return entries;
    }

    /**
     * The sum of the size-weighted normals of the wall's faces on this
     * rank's owned cells (summed over the ranks, the wall's mean direction).
     */
    const Tensor<1, dim> &
    owned_normal_sum(const unsigned int wall) const
    {
      return owned_normal_sums[wall];
    }

  private:
    std::vector<NodeOnWall>     entries;
    std::vector<Tensor<1, dim>> owned_normal_sums;
  };
} // namespace mpm

#endif
