#ifndef mpm_boundary_point_loads_h
#define mpm_boundary_point_loads_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <mpm/base/shape.h>
#include <mpm/points/material_points.h>

#include <memory>

namespace mpm
{
  using namespace dealii;

  /**
   * A load on the material points that start inside a box: either a total
   * force spread over them in proportion to their volume (a tip load on a
   * cantilever), or a traction on the surface they stand for, each point
   * carrying the face of its initial box normal to a given axis (a
   * pressure on the top layer of an oedometer sample). Both are dead
   * loads. The load factor, a function of time, scales them and gravity.
   */
  template <int dim>
  class PointLoads
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Parse the `Loads` subsection at top level. `ramped` is the default
     * of the load factor when none is given: t / end_time if true (the
     * quasi-static pseudo-time), 1 otherwise.
     */
    PointLoads(ParameterHandler &prm, bool ramped, double end_time);

    /** With a load, the points carry it: the slot "point_load". */
    void
    request_point_slots(PointSlots &slots) const
    {
      if (active)
        slots.request("point_load", dim, true);
    }

    /** Whether the scene has a load. */
    bool
    is_active() const
    {
      return active;
    }

    /** The factor on loads and gravity at time t. */
    double
    load_factor(double t) const;

    /** Write each point's share of the full load into its properties. */
    void
    apply(MaterialPoints<dim> &points) const;

  private:
    bool           active = false;
    bool           is_traction = false;
    unsigned int   traction_normal = 1;
    /** +1, -1: the loaded face is at x_p +- l_p / 2; 0: no side given. */
    int            traction_side = 0;
    /** The points that start in it carry the load. */
    std::unique_ptr<Shape<dim>> region;
    /** Total force [N] or traction [Pa], at full load. */
    Tensor<1, dim> load;
    bool           ramped;
    double         end_time;
    std::unique_ptr<FunctionParser<1>> load_factor_function;
  };
} // namespace mpm

#endif
