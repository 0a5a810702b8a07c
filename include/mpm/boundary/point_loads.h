#ifndef mpm_boundary_point_loads_h
#define mpm_boundary_point_loads_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <mpm/points/material_points.h>

namespace mpm
{
  using namespace dealii;

  /**
   * A total force spread over the material points that start inside a box,
   * in proportion to their volume: a surface load on the top layer of an
   * oedometer sample, or a tip load on a cantilever. The quasi-static scheme
   * ramps it with the load factor.
   */
  template <int dim>
  class PointLoads
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /** Parse the `Loads` subsection at top level. */
    explicit PointLoads(ParameterHandler &prm);

    /** Whether the scene has a load. */
    bool
    is_active() const
    {
      return active;
    }

    /** Write each point's share of the load into its properties. */
    void
    apply(MaterialPoints<dim> &points) const;

  private:
    bool           active = false;
    Point<dim>     lower_corner;
    Point<dim>     upper_corner;
    Tensor<1, dim> total_force;
  };
} // namespace mpm

#endif
