#include <deal.II/base/mpi.h>

#include <mpm/boundary/point_loads.h>
#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>

#include <cmath>

namespace mpm
{
  template <int dim>
  void
  PointLoads<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Loads");
    prm.declare_entry("Total force", "", Patterns::Anything(),
                      "Force at full load, one component per dimension, "
                      "spread over the points that start inside the region "
                      "in proportion to their volume [N; N/m in plane "
                      "strain; N on the plate in plane stress; N on the "
                      "full ring in axisymmetry]. Empty: "
                      "no force. Give this or Traction, not both.");
    prm.declare_entry("Traction", "", Patterns::Anything(),
                      "Traction at full load, one component per dimension "
                      "[Pa], on the surface that the points starting inside "
                      "the region stand for: each carries the face of its "
                      "initial box normal to Traction normal, V_p / l_p "
                      "with l_p its edge along that axis, so the region "
                      "should hold one layer of points. A dead load (fixed "
                      "direction and reference area). Empty: no traction.");
    prm.declare_entry("Traction normal", "y",
                      Patterns::Selection("x|y|z|+x|-x|+y|-y|+z|-z"),
                      "The axis normal to the loaded surface, and with a "
                      "sign the side of each point's box that is the "
                      "surface: +x its face at x_p + l_p / 2 (an outer "
                      "surface), -x the one at x_p - l_p / 2. The sign "
                      "matters only in an axisymmetric scene, for a "
                      "surface normal to the radius, whose area is 2 pi "
                      "r l_y at the face's radius r; there it must be "
                      "given.");
    prm.declare_entry("Region lower corner", "", Patterns::Anything(),
                      "Lower corner of the box that selects the loaded "
                      "points.");
    prm.declare_entry("Region upper corner", "", Patterns::Anything(),
                      "Upper corner of the box that selects the loaded "
                      "points.");
    prm.declare_entry("Load factor", "", Patterns::Anything(),
                      "Factor on the loads above and on gravity, a function "
                      "of the time t (the pseudo-time of the quasi-static "
                      "scheme), e.g. 'min(2*t, 1)'. Empty: t / End time "
                      "for the quasi-static scheme, 1 for the others.");
    prm.leave_subsection();
  }



  template <int dim>
  PointLoads<dim>::PointLoads(ParameterHandler &prm,
                              const bool        ramped,
                              const double      end_time)
    : ramped(ramped)
    , end_time(end_time)
  {
    prm.enter_subsection("Loads");
    const std::string force    = prm.get("Total force");
    const std::string traction = prm.get("Traction");
    if (!force.empty() && !traction.empty())
      throw InputError("Loads: give Total force or Traction, not both.");
    if (!force.empty() || !traction.empty())
      {
        active      = true;
        is_traction = !traction.empty();
        load        = is_traction ?
                        parse_point<dim>(traction, "Loads/Traction") :
                        parse_point<dim>(force, "Loads/Total force");
        const std::string normal = prm.get("Traction normal");
        traction_normal          = normal.back() - 'x';
        traction_side = normal[0] == '+' ? 1 : normal[0] == '-' ? -1 : 0;
        if (traction_normal >= dim)
          throw InputError("Loads/Traction normal = z needs Dimension = 3.");
        region = std::make_unique<BoxShape<dim>>(
          parse_point<dim>(prm.get("Region lower corner"),
                           "Loads/Region lower corner"),
          parse_point<dim>(prm.get("Region upper corner"),
                           "Loads/Region upper corner"));
      }
    const std::string factor = prm.get("Load factor");
    if (!factor.empty())
      load_factor_function =
        parse_function<1>({factor}, "t", Point<1>(), "Loads/Load factor");
    prm.leave_subsection();
    // A factor that is not finite somewhere in the run is an input error;
    // find it now rather than at that step.
    for (unsigned int k = 0; k <= 100; ++k)
      load_factor(k * end_time / 100.);
  }



  template <int dim>
  double
  PointLoads<dim>::load_factor(const double t) const
  {
    if (!load_factor_function)
      return ramped ? t / end_time : 1.;
    const double factor = load_factor_function->value(Point<1>(t));
    if (!std::isfinite(factor))
      throw InputError("Loads/Load factor is not finite at t = " +
                       std::to_string(t) + ".");
    return factor;
  }



  template <int dim>
  void
  PointLoads<dim>::apply(MaterialPoints<dim> &points) const
  {
    if (!active)
      return;
    using Layout = PointLayout<dim>;
    auto inside  = [&](const Point<dim> &x) { return region->contains(x); };
    const bool radial_surface = is_traction &&
                                points.get_grid().geometry().kind() ==
                                  Geometry<dim>::Kind::axisymmetric &&
                                traction_normal == 0;
    if (radial_surface && traction_side == 0)
      throw InputError("Loads/Traction normal = x in an axisymmetric scene: "
                       "say which face of the points' boxes is the loaded "
                       "surface, +x (an outer surface) or -x (an inner "
                       "one); its area is 2 pi r l_y at that face's "
                       "radius.");
    double volume = 0.;
    for (const auto &particle : points.handler())
      if (inside(particle.get_location()))
        volume += particle.get_properties()[Layout::reference_volume];
    volume = Utilities::MPI::sum(volume, points.get_communicator());
    if (!(volume > 0.))
      throw InputError("Loads: no material point starts inside the region "
                       "between Region lower corner and Region upper "
                       "corner.");
    const unsigned int point_load = points.slot_index("point_load");
    for (auto &particle : points.handler())
      if (inside(particle.get_location()))
        {
          const ArrayView<double> p = particle.get_properties();
          const double            V = p[Layout::reference_volume];
          double                  share =
            is_traction ? V / p[Layout::reference_size + traction_normal] :
                          V / volume;
          // V / l_x is 2 pi x_p l_y; the face lies half a box away.
          if (radial_surface)
            {
              const double x = particle.get_location()[0];
              share *= (x + 0.5 * traction_side * p[Layout::reference_size]) /
                       x;
            }
          for (unsigned int d = 0; d < dim; ++d)
            p[point_load + d] = load[d] * share;
        }
  }



  template class PointLoads<2>;
  template class PointLoads<3>;
} // namespace mpm
