#include <mpm/base/input_error.h>
#include <mpm/time/time_scheme.h>

namespace mpm
{
  template <int dim>
  void
  TimeScheme<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    prm.declare_entry("Scheme", "explicit",
                      Patterns::Selection("explicit|quasi-static|Newmark"),
                      "explicit: dynamic explicit MPM with the Update "
                      "scheme below. quasi-static: equilibrium in Load steps "
                      "over the pseudo-time End time, loads and gravity "
                      "ramped with Loads/Load factor (t / End time unless "
                      "given), solved by Newton (see "
                      "Newton). Newmark: implicit dynamic MPM with the fixed "
                      "Time step, solved by Newton (see Newton, Newmark).");
    prm.declare_entry("End time", "1", Patterns::Double(0.),
                      "Simulated time at which the run ends [s].");
    prm.declare_entry("Time step", "0", Patterns::Double(0.),
                      "Fixed time step [s]. 0 chooses every step from the "
                      "CFL number: dt = CFL h / (c + |v|_max), with h the "
                      "smallest cell edge and c the largest signal speed of "
                      "the points (the p-wave speed of their current "
                      "stiffness, plus a viscous term for a law with bulk "
                      "viscosity). A fixed step above the stability limit "
                      "h / (c + |v|_max) is refused at the start, and stops "
                      "the run if the state outgrows it later.");
    prm.leave_subsection();
  }



  template <int dim>
  std::string
  TimeScheme<dim>::scheme_name(ParameterHandler &prm)
  {
    return time_stepping_entry(prm, "Scheme");
  }



  template <int dim>
  void
  TimeScheme<dim>::request_point_slots(ParameterHandler &prm,
                                       PointSlots &      slots)
  {
    if (scheme_name(prm) == "explicit")
      return;
    slots.request("acceleration", dim, true);
    slots.request("point_load", dim, true);
  }



  template <int dim>
  std::string
  TimeScheme<dim>::time_stepping_entry(ParameterHandler & prm,
                                       const std::string &entry)
  {
    prm.enter_subsection("Time stepping");
    const std::string value = prm.get(entry);
    prm.leave_subsection();
    return value;
  }



  template <int dim>
  double
  TimeScheme<dim>::time_stepping_number(ParameterHandler & prm,
                                        const std::string &entry)
  {
    prm.enter_subsection("Time stepping");
    const double value = prm.get_double(entry);
    prm.leave_subsection();
    return value;
  }



  template <int dim>
  TimeScheme<dim>::TimeScheme(ParameterHandler &prm, const Scene &scene)
    : scene(scene)
  {
    final_time      = time_stepping_number(prm, "End time");
    fixed_time_step = time_stepping_number(prm, "Time step");
  }



  template class TimeScheme<2>;
  template class TimeScheme<3>;
} // namespace mpm
