#ifndef mpm_assembly_grid_field_h
#define mpm_assembly_grid_field_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/point.h>
#include <deal.II/particles/particle_handler.h>

#include <mpm/basis/grid_basis.h>
#include <mpm/basis/support.h>
#include <mpm/grid/grid.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * A quantity that a law reads at its points and that is computed on the
   * grid: projected from the points to the nodes in the pass that projects
   * their mass (begin_projection(), add_point(), finish_projection()),
   * solved on the grid where it needs a solve (solve(), between the nodal
   * solve and the stress update: a field that obeys an equation on the
   * grid's scalar node numbering, with its hanging-node constraints), and
   * read back at a point from the point's support (value()).
   *
   * A law names the fields it reads (Material::grid_fields()); the
   * transfer builds each field the scene's laws name once, by its name in
   * the registry, and hands a law the values of its fields at each point
   * (StepKinematics::grid_field()). A field is one new file that registers
   * itself (MPM_REGISTER_GRID_FIELD).
   */
  template <int dim>
  class GridField
  {
  public:
    virtual ~GridField() = default;

    /** Before a projection of the points' mass. */
    virtual void
    begin_projection() = 0;

    /**
     * During it: a point with properties p at x, with this support (the
     * support's nodes are grid node ids).
     */
    virtual void
    add_point(const Support<dim> &           support,
              const ArrayView<const double> &p,
              const Point<dim> &             x) = 0;

    /**
     * After it: sum the nodal values across ranks, so that owned and ghost
     * nodes hold them. Collective.
     */
    virtual void
    finish_projection(const Particles::ParticleHandler<dim> &handler) = 0;

    /**
     * Between the nodal solve and the stress update: solve what the field
     * obeys on the grid. Collective. A field that is its projection needs
     * nothing here.
     */
    virtual void
    solve()
    {}

    /** The field at a point with this support. */
    virtual double
    value(const Support<dim> &support) const = 0;

    /** What builds a field on a grid and its basis. */
    using Factory = std::function<std::unique_ptr<GridField<dim>>(
      const Grid<dim> &,
      const GridBasis<dim> &)>;

    /**
     * Add a field under its name, which is also the name a law uses for it
     * and the one the messages show. Returns true, for the static that
     * calls it (MPM_REGISTER_GRID_FIELD).
     */
    static bool
    register_field(const std::string &name, const Factory &factory);

    /** Build the field of that name (InternalError if there is none). */
    static std::unique_ptr<GridField<dim>>
    create(const std::string &    name,
           const Grid<dim> &      grid,
           const GridBasis<dim> & basis);
  };
} // namespace mpm

/**
 * Register the GridField subclass `Class` (a template on dim, built from a
 * Grid and a GridBasis) under `name`, in 2D and 3D, at the end of its own
 * source file.
 */
#define MPM_REGISTER_GRID_FIELD(Class, name)                                 \
  namespace                                                                  \
  {                                                                          \
    template <int dim>                                                       \
    std::unique_ptr<::mpm::GridField<dim>>                                   \
    create_##Class(const ::mpm::Grid<dim> &grid,                             \
                   const ::mpm::GridBasis<dim> &basis)                       \
    {                                                                        \
      return std::make_unique<Class<dim>>(grid, basis);                      \
    }                                                                        \
    const bool Class##_registered_2d =                                       \
      ::mpm::GridField<2>::register_field(name, &create_##Class<2>);         \
    const bool Class##_registered_3d =                                       \
      ::mpm::GridField<3>::register_field(name, &create_##Class<3>);         \
  }

#endif
