#ifndef mpm_points_grid_adaptation_h
#define mpm_points_grid_adaptation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/cell_id.h>

#include <mpm/grid/grid.h>
#include <mpm/points/material_points.h>

#include <boost/serialization/split_member.hpp>

#include <functional>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * A background grid that follows the material (`Adaptive grid`).
   *
   * The grid of the scene (Generator and Global refinements) is the
   * coarsest the grid gets. Cells within `Margin` cells of material are
   * refined `Refinement levels` times more, and cells that material has
   * left far behind are coarsened again, so that the cost of a step and
   * the memory of the nodes follow the material, not the box. p4est keeps
   * neighbouring cells within one level of each other; the vertices that
   * hang on a coarser cell's face take their values from that face's nodes
   * (GridBasis), in the explicit projection as in the output.
   *
   * "Within n cells" is measured by rings: the cells that hold material,
   * then the cells that share a vertex with them, and so on, n times;
   * ranks share the rings through the nodes on their boundary.
   *
   * When: every step, if a point lies in a cell that is not at the finest
   * level (the only check that a correct run needs: every point is
   * projected from a finest cell); and every `Check interval` steps, if a
   * cell within Margin rings is not at the finest level. The grid is then
   * refined out to 2 Margin rings, so that material must cross Margin
   * cells before the next refinement. The cells beyond 3 Margin rings
   * coarsen at a check once they make up a tenth of the grid. Each change
   * carries the points into their new cells.
   */
  template <int dim>
  class GridAdaptation
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /** Whether a cell holds material: a point, or a body's region. */
    using Occupied = std::function<bool(
      const typename Triangulation<dim>::active_cell_iterator &)>;

    /**
     * Parse the `Adaptive grid` subsection (the handler is at top level).
     * `reserved`: the cells that material will fill later (the inflows'
     * regions), kept refined as if they held points.
     */
    GridAdaptation(ParameterHandler &         prm,
                   Grid<dim> &                grid,
                   const MaterialPoints<dim> &points,
                   const Occupied &           reserved,
                   ConditionalOStream &       pcout);

    /** Whether the grid adapts (Refinement levels > 0). */
    bool
    enabled() const
    {
      return levels > 0;
    }

    /**
     * Before any point is seeded: refine around the cells that `occupied`
     * says will hold material (the bodies' regions), out to 2 Margin rings,
     * so that the points are seeded into the finest cells.
     */
    void
    refine_around(const Occupied &occupied);

    /**
     * At the top of a step: adapt to the points if due (see the class
     * documentation). Returns whether the grid changed.
     */
    bool
    check(const unsigned int step);

    /** How often check() changed the grid in this run. */
    unsigned int
    n_adaptations() const
    {
      return adaptations;
    }

    /**
     * For Checkpoint, before the load balance and the points: the active
     * cells. load() refines and coarsens the scene's grid until it has the
     * same cells, so that the points load into them.
     */
    template <class Archive>
    void
    save(Archive &archive, const unsigned int) const;

    template <class Archive>
    void
    load(Archive &archive, const unsigned int);

    BOOST_SERIALIZATION_SPLIT_MEMBER()

  private:
    static constexpr unsigned int beyond = static_cast<unsigned int>(-1);

    /**
     * Per active cell index (owned cells only): the ring of the cell, 0 for
     * the cells that `occupied` names, up to `n_rings`; `beyond` further
     * away.
     */
    std::vector<unsigned int>
    rings(const Occupied &occupied, const unsigned int n_rings) const;

    /**
     * Refine out to 2 Margin rings, level by level, when `refine` or a cell
     * within Margin rings is coarser than the finest; then coarsen beyond
     * 3 Margin rings if due. Returns whether the grid changed.
     */
    bool
    adapt(const Occupied &occupied, const bool refine);

    /** The points' cells. */
    bool
    holds_points(
      const typename Triangulation<dim>::active_cell_iterator &cell) const
    {
      return points.handler().n_particles_in_cell(cell) > 0;
    }

    Grid<dim> &                grid;
    const MaterialPoints<dim> &points;
    const Occupied             reserved;
    ConditionalOStream &       pcout;

    unsigned int levels;
    unsigned int margin;
    unsigned int interval;
    /** base level + levels. */
    int          finest_level;
    unsigned int adaptations = 0;
  };
} // namespace mpm

#endif
