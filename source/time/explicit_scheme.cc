#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/base/shared_position.h>
#include <mpm/time/explicit_scheme.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  ExplicitScheme<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    prm.declare_entry("CFL number", "0.3", Patterns::Double(0., 1.),
                      "Fraction of the stability limit used by the automatic "
                      "time step, 0 < CFL <= 1.");
    prm.declare_entry("Update scheme", "MUSL",
                      Patterns::Selection("USF|USL|MUSL"),
                      "Order of the explicit update: USF (update stress "
                      "first), USL (update stress last), MUSL (modified USL, "
                      "Wieckowski 2004 section 3.5).");
    prm.declare_entry("PIC fraction", "0", Patterns::Double(0., 1.),
                      "Explicit: share of the PIC velocity, N (v + dt a), in "
                      "the point velocity update; the rest is FLIP, v_p + dt "
                      "N a. 0 is pure FLIP, as [W], which conserves energy "
                      "but keeps point velocities the grid cannot see (in a "
                      "settled granular deposit they never die out). A few "
                      "percent damps them within tens of steps at the cost "
                      "of a little dissipation; 1 is pure PIC, strongly "
                      "dissipative.");
    prm.declare_entry(
      "Dilatation rate", "point",
      Patterns::Selection("point|cell average"),
      "Explicit: the volumetric part of each point's velocity gradient. "
      "point: its own. cell average: the mean over the points of its cell, "
      "weighted by their volumes (a B-bar in rate form, after Mast et al. "
      "2012 and Coombs et al. 2018): bilinear cells with 2 x 2 points "
      "cannot follow isochoric plastic flow (von Mises, Tresca, Mohr-"
      "Coulomb without dilatancy) point by point and lock, which raises "
      "forming pressures and bearing capacities; the average lets them "
      "flow. Plane strain, axisymmetric (the hoop rate included) and 3D.");
    prm.declare_entry(
      "Velocity projection", "lumped",
      Patterns::Selection("lumped|corrected"),
      "Explicit: how the point momenta become nodal velocities. lumped: "
      "v = sum m_p N v_p / sum m_p N. The point velocities are sums of "
      "nodal updates, so each step passes them through this smoothing "
      "again: a wave loses frequency, in 1D (kh)^2/12 of it, three times "
      "the lumped mass's own dispersion. corrected: one Jacobi step towards "
      "the consistent-mass projection, v += M_L^-1 sum m_p N (v_p - "
      "v(x_p)), which leaves only the lumped mass's dispersion, at the cost "
      "of one more pass over the points per projection. Momentum is kept "
      "exactly and the stable time step is the same.");
    prm.declare_entry(
      "Mass matrix", "lumped", Patterns::Selection("lumped|blended"),
      "Explicit: the mass the nodal accelerations are solved with. lumped: "
      "a = f / sum m_p N. Its dispersion makes waves slow, in 1D by "
      "(kh)^2/24 of their frequency (the period of a bar on 16 cells is "
      "0.04 % long, a phase error of 1 % of the amplitude after four "
      "periods). blended: half a Jacobi step from the lumped mass towards "
      "the consistent one, which solves with the mean of the two to "
      "O((kh)^4) and cancels the dispersion (Krieg and Key 1973), at the "
      "cost of one more pass over the points a step. Walls keep holding: a "
      "fixed or slip wall projects the change as it projects velocities; a "
      "friction wall or an obstacle applies its Coulomb law again to the "
      "velocity the node would reach with the change, and reports the "
      "force of that. No mode speeds up by more "
      "than sqrt(1.5), so the stability limit that CFL number and a fixed "
      "Time step are measured against is that much smaller. With the "
      "corrected velocity projection the smooth modes' periods are then "
      "exact to O((kh)^4).");
    prm.leave_subsection();
  }



  template <int dim>
  std::vector<std::string>
  ExplicitScheme<dim>::entries_set(ParameterHandler &prm)
  {
    ParameterHandler defaults;
    declare_parameters(defaults);
    std::vector<std::string> set;
    prm.enter_subsection("Time stepping");
    defaults.enter_subsection("Time stepping");
    for (const std::string entry : {"CFL number",
                                    "Update scheme",
                                    "PIC fraction",
                                    "Dilatation rate",
                                    "Velocity projection",
                                    "Mass matrix"})
      {
        const bool number = entry == "CFL number" || entry == "PIC fraction";
        if (number ? prm.get_double(entry) != defaults.get_double(entry) :
                     prm.get(entry) != defaults.get(entry))
          set.push_back(entry);
      }
    defaults.leave_subsection();
    prm.leave_subsection();
    return set;
  }



  template <int dim>
  ExplicitScheme<dim>::ExplicitScheme(
    ParameterHandler &                         prm,
    const typename TimeScheme<dim>::Scene &scene)
    : TimeScheme<dim>(prm, scene)
    , cfl_number(TimeScheme<dim>::time_stepping_number(prm, "CFL number"))
    , integrator(scene.transfer,
                 scene.materials,
                 ExplicitIntegrator<dim>::parse_scheme(
                   TimeScheme<dim>::time_stepping_entry(prm, "Update scheme")),
                 TimeScheme<dim>::time_stepping_number(prm, "PIC fraction"),
                 TimeScheme<dim>::time_stepping_entry(prm, "Dilatation rate") ==
                   "cell average",
                 scene.grid,
                 scene.timer)
  {
    if (scene.grid.geometry().kind() == Geometry<dim>::Kind::plane_stress &&
        TimeScheme<dim>::time_stepping_entry(prm, "Dilatation rate") !=
          "point")
      throw InputError("Time stepping/Dilatation rate = cell average is for "
                       "plane strain, axisymmetric and 3D scenes: a plate in "
                       "plane stress thins instead of locking.");
    if (TimeScheme<dim>::time_stepping_entry(prm, "Velocity projection") ==
        "corrected")
      scene.transfer.enable_corrected_velocity_projection();
    if (TimeScheme<dim>::time_stepping_entry(prm, "Mass matrix") == "blended")
      {
        // Its change of the accelerations would undo the contact's at the
        // nodes where the fields meet.
        if (scene.transfer.couples_fields())
          throw InputError("Time stepping/Mass matrix = blended does not run "
                           "with bodies in several Contact groups: use the "
                           "lumped mass.");
        scene.transfer.enable_blended_mass();
      }
  }



  template <int dim>
  void
  ExplicitScheme<dim>::check_start() const
  {
    if (this->fixed_time_step > 0.)
      {
        const double limit = stability_limit(current_speeds());
        if (this->fixed_time_step > limit)
          throw InputError(fixed_step_beyond(limit) +
                           ". Use a smaller step, or 0 for an automatic one.");
      }
  }



  template <int dim>
  void
  ExplicitScheme<dim>::start()
  {
    speeds = current_speeds();
  }



  template <int dim>
  void
  ExplicitScheme<dim>::points_added()
  {
    const Speeds now = current_speeds();
    speeds.point     = std::max(speeds.point, now.point);
    speeds.signal    = std::max(speeds.signal, now.signal);
  }



  template <int dim>
  double
  ExplicitScheme<dim>::advance(const double time, const unsigned int step)
  {
    const double end = this->end_time();
    const double dt  = this->step_to_end(time,
                                        this->fixed_time_step > 0. ?
                                          this->fixed_time_step :
                                          stable_time_step(speeds));

    this->scene.transfer.set_load_factor(this->scene.loads.load_factor(time));
    this->scene.transfer.set_time(time);
    const auto     report = integrator.step(dt);
    check_step(report, time, step, dt);
    const MPI_Comm communicator = this->scene.points.get_communicator();
    speeds.point  = Utilities::MPI::max(report.max_speed, communicator);
    speeds.signal = Utilities::MPI::max(report.max_signal_speed, communicator);

    // A fixed Time step that the state has outgrown (a stiffening law)
    // stops the run.
    const bool last_step = time + dt >= end - this->end_time_tolerance();
    if (this->fixed_time_step > 0. && !last_step)
      {
        const double limit = stability_limit(speeds);
        if (this->fixed_time_step > limit)
          {
            std::ostringstream message;
            message << "After step " << step + 1 << " (t = " << time + dt
                    << ") " << fixed_step_beyond(limit)
                    << ": the material has stiffened or the points have sped "
                       "up. The last good state is in the output written so "
                       "far. Use a smaller step, or 0 for an automatic one.";
            throw RunError(message.str());
          }
      }
    return dt;
  }



  template <int dim>
  typename ExplicitScheme<dim>::Speeds
  ExplicitScheme<dim>::current_speeds() const
  {
    using Layout = PointLayout<dim>;
    Speeds speeds;
    for (const auto &particle : this->scene.points.handler())
      {
        const ArrayView<const double> p = particle.get_properties();
        const Material &              material =
          *this->scene.materials[static_cast<unsigned int>(
            p[Layout::material_id])];
        speeds.point = std::max(speeds.point, Layout::get_velocity(p).norm());
        speeds.signal =
          std::max(speeds.signal,
                   material.signal_speed(
                     Layout::get_stress(p),
                     ArrayView<const double>(&p[Layout::internal_variables],
                                             material.n_internal_variables()),
                     this->scene.grid.minimum_cell_size()));
      }
    const MPI_Comm communicator = this->scene.points.get_communicator();
    speeds.point  = Utilities::MPI::max(speeds.point, communicator);
    speeds.signal = Utilities::MPI::max(speeds.signal, communicator);
    return speeds;
  }



  template <int dim>
  double
  ExplicitScheme<dim>::stability_limit(const Speeds &speeds) const
  {
    // The blended mass speeds no mode up by more than sqrt(1 + 1/2)
    // (GridTransfer::correct_towards_consistent_mass()).
    return this->scene.grid.minimum_cell_size() /
           (speeds.signal + speeds.point) /
           (this->scene.transfer.has_blended_mass() ? std::sqrt(1.5) : 1.);
  }



  template <int dim>
  double
  ExplicitScheme<dim>::stable_time_step(const Speeds &speeds) const
  {
    // With every point gone (through an outflow boundary) nothing limits
    // the step: the run goes to End time.
    if (this->scene.points.n_global_points() == 0)
      return std::numeric_limits<double>::infinity();
    double step = cfl_number * stability_limit(speeds);
    // Everything at rest and stress-free (loose fill just released): the
    // step in which gravity moves a point from rest by the CFL share of a
    // cell, CFL h = g dt^2 (the explicit update moves it by g dt^2).
    const double g = this->scene.transfer.gravity_vector().norm();
    if (speeds.signal == 0. && speeds.point == 0. && g > 0.)
      step = std::sqrt(cfl_number * this->scene.grid.minimum_cell_size() / g);
    // Every rank has the same speeds, so every rank throws.
    if (!(step > 0. && std::isfinite(step)))
      throw RunError("The explicit time step is not defined: the largest "
                     "signal speed is " + std::to_string(speeds.signal) +
                     " m/s and the fastest point moves at " +
                     std::to_string(speeds.point) +
                     " m/s (every point has come apart and rests with no "
                     "gravity, or a law "
                     "overflowed).");
    return step;
  }



  template <int dim>
  std::string
  ExplicitScheme<dim>::fixed_step_beyond(const double limit) const
  {
    std::ostringstream message;
    message << "Time stepping/Time step = " << this->fixed_time_step
            << " exceeds the explicit stability limit " << limit
            << " (smallest cell edge " << this->scene.grid.minimum_cell_size()
            << " over the largest signal speed plus the fastest point)";
    return message.str();
  }



  template <int dim>
  void
  ExplicitScheme<dim>::check_step(
    const typename ExplicitIntegrator<dim>::StepReport &report,
    const double                                         time,
    const unsigned int                                   step,
    const double                                         dt) const
  {
    const MPI_Comm communicator = this->scene.points.get_communicator();
    // Every rank takes part, so every rank throws the same error.
    const bool failed = Utilities::MPI::logical_or(report.failed, communicator);
    if (failed)
      {
        // The reason of the point that is named, so the text is the same
        // on any number of ranks.
        const auto [where, rank] = shared_position_and_rank(
          report.failed, report.failed_position, communicator);
        const std::string reason = Utilities::MPI::all_gather(
          communicator, report.failed ? report.failure : std::string())[rank];
        std::ostringstream message;
        message << "The run went unstable in step " << step + 1 << " (t = "
                << time + dt << ", dt = " << dt << "): " << reason << ", at "
                << where
                << ". The last good state is in the output written so far. "
                   "Try a smaller Time stepping/CFL number or Time step.";
        throw RunError(message.str());
      }

    const double max_fraction =
      Utilities::MPI::max(report.max_cell_fraction, communicator);
    if (max_fraction > 1.)
      {
        const std::string where =
          shared_position(report.max_cell_fraction >=
                            max_fraction * (1. - 1e-12),
                          report.fastest_position,
                          communicator);
        std::ostringstream message;
        message << "In step " << step + 1 << " (t = " << time + dt
                << ", dt = " << dt << ") the material point at " << where
                << " would move " << max_fraction
                << " cell widths, more than the one cell a step allows. "
                   "Reduce Time stepping/Time step or CFL number.";
        throw RunError(message.str());
      }
  }



  template <int dim>
  std::vector<std::string>
  ExplicitScheme<dim>::entries_that_may_change() const
  {
    // A continued run may go on further, or with smaller steps (after a
    // run that went unstable).
    return {"Time stepping/End time",
            "Time stepping/Time step",
            "Time stepping/CFL number"};
  }



  template <int dim>
  void
  ExplicitScheme<dim>::save(boost::archive::binary_oarchive &archive) const
  {
    archive << speeds.point << speeds.signal;
  }



  template <int dim>
  void
  ExplicitScheme<dim>::load(boost::archive::binary_iarchive &archive)
  {
    archive >> speeds.point >> speeds.signal;
  }



  template class ExplicitScheme<2>;
  template class ExplicitScheme<3>;
} // namespace mpm
