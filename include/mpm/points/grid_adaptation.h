#ifndef mpm_points_grid_adaptation_h
#define mpm_points_grid_adaptation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/cell_id.h>

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
#include <mpm/base/shape.h>
#include <mpm/grid/grid.h>
#include <mpm/points/material_points.h>

#include <boost/serialization/split_member.hpp>

#include <functional>
#include <memory>
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
   * When: every step, if a point lies in a cell coarser than `Refinement
   * levels` (the only check that a correct run needs: every point is
   * projected from a cell of its level); and every `Check interval` steps,
   * if a cell within Margin rings is coarser than it needs. The grid is then
   * refined out to 2 Margin rings, so that material must cross Margin
   * cells before the next refinement. The cells beyond 3 Margin rings
   * coarsen at a check once they make up a tenth of the grid. Each change
   * carries the points into their new cells.
   *
   * `Finer levels` refine some of the material further: the material whose
   * points lie in `Finer region`, or whose equivalent plastic strain grew
   * faster than `Finer plastic strain rate` since the last check (the
   * flowing zone of a collapse, the shear band under a footing). Such
   * cells, with their Margin rings, go to the finest level; the rest of
   * the material stays at `Refinement levels`, and the vertices between
   * the two hang as they do at the material's edge. The rate is measured
   * at each check, over the time since the one before; each point keeps
   * its plastic strain at the last check for that
   * (MaterialPoints::plastic_strain_record_index()).
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
     * Where `Finer where` names the plastic strain rate, the points keep
     * their plastic strain at the last check: the slot
     * "plastic_strain_at_last_check" (the handler is at top level).
     */
    static void
    request_point_slots(ParameterHandler &prm, PointSlots &slots);

    /**
     * Parse the `Adaptive grid` subsection (the handler is at top level).
     * `reserved`: the cells that material will fill later (the inflows'
     * regions), kept refined as if they held points. `plastic_law`: per
     * material id, whether its points carry an equivalent plastic strain
     * (the first internal variable).
     */
    GridAdaptation(ParameterHandler &         prm,
                   Grid<dim> &                grid,
                   MaterialPoints<dim> &      points,
                   const Occupied &           reserved,
                   const std::vector<bool> &  plastic_law,
                   ConditionalOStream &       pcout);

    /**
     * The grid adapts with MPM's linear shape functions only (InputError
     * otherwise).
     */
    void
    check_scene(const SceneChoices &choices,
                const bool          linear_shape_functions) const
    {
      if (enabled() && (choices.meshfree() || !linear_shape_functions))
        throw InputError("Adaptive grid/Refinement levels or Finer levels > "
                         "0 needs Method = MPM and Grid/Shape functions = "
                         "linear; the meshfree methods and the smooth shape "
                         "functions take a fixed grid.");
    }

    /** Whether the grid adapts (Refinement levels or Finer levels > 0). */
    bool
    enabled() const
    {
      return finest_level > static_cast<int>(grid.base_level());
    }

    /**
     * Before any point is seeded: refine around the cells that `occupied`
     * says will hold material (the bodies' regions), out to 2 Margin rings,
     * so that the points are seeded into the finest cells.
     */
    void
    refine_around(const Occupied &occupied);

    /**
     * At the top of a step, at `time`: adapt to the points if due (see the
     * class documentation). Returns whether the grid changed.
     */
    bool
    check(const unsigned int step, const double time);

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
     * Per active cell index (owned cells only), the rings around the
     * material and around the material that gets the Finer levels (empty
     * without them).
     */
    struct Rings
    {
      std::vector<unsigned int> material;
      std::vector<unsigned int> finer;
    };

    /** The level a cell needs when it lies within `reach` of the rings. */
    int
    wanted_level(const Rings &      rings,
                 const unsigned int cell_index,
                 const unsigned int reach) const
    {
      if (!rings.finer.empty() && rings.finer[cell_index] <= reach)
        return finest_level;
      if (rings.material[cell_index] <= reach)
        return material_level;
      return static_cast<int>(grid.base_level());
    }

    /**
     * Per active cell index (owned cells only): the ring of the cell, 0 for
     * the cells that `occupied` names, up to `n_rings`; `beyond` further
     * away.
     */
    std::vector<unsigned int>
    rings(const Occupied &occupied, const unsigned int n_rings) const;

    Rings
    rings(const Occupied &     occupied,
          const Occupied &     finer,
          const unsigned int   n_rings) const;

    /**
     * Refine out to 2 Margin rings, level by level, when `refine` or a cell
     * within Margin rings is coarser than it needs to be; then coarsen
     * beyond 3 Margin rings if due. `finer`: the cells of the material that
     * gets the Finer levels. Returns whether the grid changed.
     */
    bool
    adapt(const Occupied &occupied, const Occupied &finer, bool refine);

    /**
     * Whether a point gets the Finer levels at `time`: it lies in the
     * Finer region, or its plastic strain grew faster than the Finer
     * plastic strain rate since the last check.
     */
    bool
    gets_finer_levels(const Particles::ParticleAccessor<dim> &point,
                      const double                            time) const;

    /** After a check: each point's plastic strain, for the next rate. */
    void
    record_plastic_strain(const double time);

    /** The points' cells. */
    bool
    holds_points(
      const typename Triangulation<dim>::active_cell_iterator &cell) const
    {
      return points.handler().n_particles_in_cell(cell) > 0;
    }

    Grid<dim> &                grid;
    MaterialPoints<dim> &      points;
    const Occupied             reserved;
    const std::vector<bool>    plastic_law;
    ConditionalOStream &       pcout;

    unsigned int levels;
    unsigned int margin;
    unsigned int interval;
    /** base level + Refinement levels: every cell with material. */
    int material_level;
    /** material_level + Finer levels. */
    int finest_level;
    /** Empty unless Finer where names the region. */
    std::unique_ptr<Shape<dim>> finer_region;
    /** 0 unless Finer where names the plastic strain rate. */
    double       finer_plastic_strain_rate = 0.;
    /** When the points' plastic strains were recorded (saved). */
    double       last_record_time = 0.;
    unsigned int adaptations      = 0;
  };
} // namespace mpm

#endif
