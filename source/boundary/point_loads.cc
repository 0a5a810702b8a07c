#include <deal.II/base/mpi.h>

#include <mpm/boundary/point_loads.h>
#include <mpm/core/input_error.h>
#include <mpm/core/parse.h>

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
                      "in proportion to their volume [N, N/m in 2D]. Empty: "
                      "no load.");
    prm.declare_entry("Region lower corner", "", Patterns::Anything(),
                      "Lower corner of the box that selects the loaded "
                      "points.");
    prm.declare_entry("Region upper corner", "", Patterns::Anything(),
                      "Upper corner of the box that selects the loaded "
                      "points.");
    prm.leave_subsection();
  }



  template <int dim>
  PointLoads<dim>::PointLoads(ParameterHandler &prm)
  {
    prm.enter_subsection("Loads");
    const std::string force = prm.get("Total force");
    if (!force.empty())
      {
        active       = true;
        total_force  = parse_point<dim>(force, "Loads/Total force");
        lower_corner = parse_point<dim>(prm.get("Region lower corner"),
                                        "Loads/Region lower corner");
        upper_corner = parse_point<dim>(prm.get("Region upper corner"),
                                        "Loads/Region upper corner");
      }
    prm.leave_subsection();
  }



  template <int dim>
  void
  PointLoads<dim>::apply(MaterialPoints<dim> &points) const
  {
    if (!active)
      return;
    using Layout = PointLayout<dim>;
    auto inside  = [&](const Point<dim> &x) {
      for (unsigned int d = 0; d < dim; ++d)
        if (x[d] < lower_corner[d] || x[d] > upper_corner[d])
          return false;
      return true;
    };
    double volume = 0.;
    for (const auto &particle : points.handler())
      if (inside(particle.get_location()))
        volume += particle.get_properties()[Layout::reference_volume];
    volume = Utilities::MPI::sum(volume, points.get_communicator());
    if (!(volume > 0.))
      throw InputError("Loads: no material point starts inside the region "
                       "between Region lower corner and Region upper "
                       "corner.");
    for (auto &particle : points.handler())
      if (inside(particle.get_location()))
        {
          const ArrayView<double> p = particle.get_properties();
          for (unsigned int d = 0; d < dim; ++d)
            p[points.point_load_index() + d] =
              total_force[d] * p[Layout::reference_volume] / volume;
        }
  }



  template class PointLoads<2>;
  template class PointLoads<3>;
} // namespace mpm
