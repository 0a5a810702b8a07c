#ifndef mpm_points_material_points_h
#define mpm_points_material_points_h

#include <deal.II/distributed/tria.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/particles/particle_handler.h>

#include <boost/serialization/split_member.hpp>

#include <deal.II/base/parameter_handler.h>

#include <mpm/grid/grid.h>
#include <mpm/points/point_layout.h>
#include <mpm/points/point_slots.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * The material points of a scene, stored in a Particles::ParticleHandler
   * with the properties of PointLayout. Points move with the cells across
   * ranks when they are sorted, and into the new cells when the grid
   * changes (Grid::before_change, Grid::changed). PointSeeder puts them in.
   */
  template <int dim>
  class MaterialPoints
  {
  public:
    using Layout = PointLayout<dim>;

    /**
     * `internal_variable_names`: the internal variables every point
     * carries, named for the output; after them the slots that the scene's
     * parts asked for. With `far_moves` (the implicit schemes) a step may
     * carry a point beyond the cells next to its old one.
     */
    MaterialPoints(const Grid<dim> &               grid,
                   const std::vector<std::string> &internal_variable_names,
                   const PointSlots &              slots     = {},
                   const bool                      far_moves = false);

    /** `Boundary conditions/Outflow boundaries`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Read the outflow boundaries (the handler is at top level): points
     * that leave the grid through them are removed, and counted, instead
     * of stopping the run.
     */
    void
    parse_outflow(ParameterHandler &prm);

    /** Whether the scene has outflow boundaries. */
    bool
    has_outflow() const
    {
      return !outflow_ids.empty();
    }

    /** The mass of the points removed so far, over all ranks. */
    double
    removed_mass() const;

    /** The number of points removed so far, over all ranks. */
    types::particle_index
    removed_points() const;

    /**
     * Put every point into the cell (and onto the rank) that contains its
     * current position. A point that leaves the grid through an outflow
     * boundary is removed; one that leaves it elsewhere stops the run with
     * a RunError naming its position. In implicit runs, whose steps may
     * carry a point beyond the cells next to its old one (and so beyond
     * the ghost cells, where deal.II's sort cannot follow it), such points
     * are sent to the rank that owns their new position.
     */
    void
    sort();

    /**
     * Make room in an empty pool for `n_points` points, and for the copies
     * sort() inserts before it removes the points that moved (twice
     * moves_before_layout(), so that a step that moves that many more than
     * it allows between layouts still finds room): seeded one by one, the
     * pool would grow by doubling, and hold up to three times its size for
     * a moment. Room never written takes no memory. A pool that holds
     * points already is left to grow, which copies it rarely.
     */
    void
    make_room(const types::particle_index n_points);

    /**
     * How often sort() has laid this rank's property pool out again in cell
     * order, itself (lay_out_pool(), on the ranks where enough points
     * moved) or through deal.II's sort (on every rank).
     */
    unsigned int
    n_pool_layouts() const
    {
      return pool_layouts;
    }

    Particles::ParticleHandler<dim> &
    handler()
    {
      return particle_handler;
    }

    const Particles::ParticleHandler<dim> &
    handler() const
    {
      return particle_handler;
    }

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

    unsigned int
    n_internal_variables() const
    {
      return internal_names.size();
    }

    /** Whether the points carry the slot of that name (PointSlots). */
    bool
    has_slot(const std::string &name) const
    {
      return slots.has(name);
    }

    /** The index of the first component of a slot in a point's properties. */
    unsigned int
    slot_index(const std::string &name) const
    {
      return Layout::internal_variables + n_internal_variables() +
             slots.find(name).offset;
    }

    /** Names of all properties, for output; vectors repeat their name. */
    std::vector<std::string>
    property_names() const;

    /** The properties that are vectors (velocity and the implicit ones). */
    std::vector<unsigned int>
    vector_properties() const;

    types::particle_index
    n_global_points() const
    {
      return particle_handler.n_global_particles();
    }

    /**
     * This rank's points, for Checkpoint: cell, id, position, reference
     * position and properties, in the handler's order, which load() keeps
     * (it fixes the order of every sum over points). load() replaces the
     * points; the grid must be the one they were saved on.
     */
    template <class Archive>
    void
    save(Archive &archive, const unsigned int) const;

    template <class Archive>
    void
    load(Archive &archive, const unsigned int);

    BOOST_SERIALIZATION_SPLIT_MEMBER()

    /** The grid the points live on. */
    const Grid<dim> &
    get_grid() const
    {
      return grid;
    }

  private:
    /**
     * Take the points that moved more than the smallest cell edge along
     * some axis since the last sort out of the handler and insert them on
     * the ranks that own their positions (collective). One in no rank's
     * cells goes through the particle_lost handler.
     */
    void
    carry_far_points();

    /**
     * The sort when every point that left its cell stays on this rank and
     * in a cell next to its old one (collective; returns false, having
     * changed nothing but reference locations, where some point on some
     * rank does not). deal.II's sort copies every point's properties into
     * cell order at every call; this one moves only the points that changed
     * cells, in the order deal.II would (so every sum over points is the
     * same), and lays the pool out again (lay_out_pool()) once
     * moves_before_layout() of the points have moved since.
     */
    bool
    sort_within_rank();

    /**
     * Lay the property pool out again in the handler's order, so that the
     * points of one cell lie next to each other in memory; the order of the
     * points is unchanged. Local: the caller updates the handler's cached
     * numbers, with every rank.
     */
    void
    lay_out_pool();

    /**
     * The active cell that holds x, walking from `cell` across the faces
     * through which x lies outside (at most 2 dim of them), with x's
     * reference location there; an invalid iterator if the walk leaves the
     * rank's cells or the grid.
     */
    std::pair<typename Triangulation<dim>::active_cell_iterator, Point<dim>>
    walk_to_cell(typename Triangulation<dim>::active_cell_iterator cell,
                 Point<dim>                                        reference,
                 const Point<dim> &                                x) const;

    /** Whether x lies beyond an outflow face of `cell`. */
    bool
    leaves_through_outflow(
      const typename Triangulation<dim>::active_cell_iterator &cell,
      const Point<dim> &                                       x) const;

    const Grid<dim> &                                grid;
    const parallel::distributed::Triangulation<dim> &triangulation;
    const Mapping<dim> &                             mapping;
    Particles::ParticleHandler<dim>                  particle_handler;
    /** Finds the cell of a point that moved far (implicit runs). */
    GridTools::Cache<dim> cell_cache;
    const std::vector<std::string>  internal_names;
    const PointSlots                slots;
    const bool                      far_moves;

    /** Filled by the particle_lost signal during a sort. */
    std::vector<Point<dim>> lost_positions;

    std::vector<types::boundary_id> outflow_ids;
    /** What left through the outflow boundaries from this rank. */
    double                          local_removed_mass   = 0.;
    types::particle_index           local_removed_points = 0;

    /**
     * How many of n points may move between cells before sort() lays the
     * pool out again in cell order (so that the points of one cell stay
     * near each other in memory); make_room() sizes the pool by it too.
     */
    static types::particle_index
    moves_before_layout(const types::particle_index n)
    {
      return n / 4;
    }

    /** Points moved between cells since the pool was last laid out. */
    types::particle_index moved_since_layout = 0;
    unsigned int          pool_layouts       = 0;

    /** Between Grid::before_change and Grid::changed. */
    bool                                 grid_changing = false;
    boost::signals2::scoped_connection before_grid_change;
    boost::signals2::scoped_connection after_grid_change;
  };
} // namespace mpm

#endif
