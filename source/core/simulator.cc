#include <deal.II/base/mpi.h>

#include <mpm/core/input_error.h>
#include <mpm/core/parse.h>
#include <mpm/core/shared_position.h>
#include <mpm/boundary/point_loads.h>
#include <mpm/core/simulator.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  Simulator<dim>::declare_parameters(
    ParameterHandler &              prm,
    const std::vector<std::string> &material_names,
    const std::vector<std::string> &body_names)
  {
    prm.declare_entry("Gravity",
                      dim == 2 ? "0, 0" : "0, 0, 0",
                      Patterns::Anything(),
                      "Gravitational acceleration, one component per "
                      "dimension, e.g. '0, -9.81' [m/s^2].");

    prm.declare_entry(
      "Method", "MPM", Patterns::Selection("MPM|GMM-MLS|GMM-LME"),
      "MPM: the material point method, on the background grid's Q1 shape "
      "functions. GMM-MLS, GMM-LME: the Galerkin meshfree method (Iaconeta "
      "et al. 2017), on a cloud of nodes that starts at the grid vertices "
      "of the cells holding material and moves with it, with moving least "
      "squares or local max-entropy shape functions (see Meshfree). The "
      "meshfree methods run with the quasi-static and Newmark schemes, on "
      "one rank.");
    MeshfreeBasis<dim>::declare_parameters(prm);
    Grid<dim>::declare_parameters(prm);
    DirichletConditions<dim>::declare_parameters(prm);
    PointLoads<dim>::declare_parameters(prm);
    ImplicitIntegrator<dim>::declare_parameters(prm);

    prm.enter_subsection("Time stepping");
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
    prm.declare_entry("CFL number", "0.3", Patterns::Double(0., 1.),
                      "Fraction of the stability limit used by the automatic "
                      "time step, 0 < CFL <= 1.");
    prm.declare_entry("Scheme", "explicit",
                      Patterns::Selection("explicit|quasi-static|Newmark"),
                      "explicit: dynamic explicit MPM with the Update "
                      "scheme below. quasi-static: equilibrium in Load steps "
                      "over the pseudo-time End time, loads and gravity "
                      "ramped with Loads/Load factor (t / End time unless "
                      "given), solved by Newton (see "
                      "Newton). Newmark: implicit dynamic MPM with the fixed "
                      "Time step, solved by Newton (see Newton, Newmark).");
    prm.declare_entry("Load steps", "10", Patterns::Integer(1),
                      "Quasi-static: number of equal load steps.");
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
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("Directory", "output", Patterns::Anything(),
                      "Directory for all output; created if missing.");
    prm.declare_entry("Write ParaView output", "true", Patterns::Bool(),
                      "Write snapshots of points (and grid) for ParaView. "
                      "Off for throughput measurements.");
    prm.declare_entry("Interval", "0", Patterns::Double(0.),
                      "Simulated time between ParaView snapshots. 0 writes "
                      "the first and the last state only.");
    prm.declare_entry("Write grid", "true", Patterns::Bool(),
                      "Also write the background grid with nodal mass, "
                      "velocity and acceleration.");
    prm.declare_entry("Time series file", "time_series.csv",
                      Patterns::Anything(),
                      "CSV file (in the output directory) with time, "
                      "energies, momentum, mass, centre of mass and tracked "
                      "points.");
    prm.declare_entry("Time series interval", "0", Patterns::Double(0.),
                      "Simulated time between rows of the time series; 0 "
                      "writes every step.");
    prm.declare_entry("Tracked points", "", Patterns::Anything(),
                      "Positions, ';'-separated; the material point nearest "
                      "to each at the start is followed in the time series.");
    prm.leave_subsection();
    Checkpoint::declare_parameters(prm);

    prm.enter_subsection("Materials");
    for (const auto &name : material_names)
      {
        prm.enter_subsection(name);
        Material::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();

    prm.enter_subsection("Bodies");
    for (const auto &name : body_names)
      {
        prm.enter_subsection(name);
        Body<dim>::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }



  template <int dim>
  Simulator<dim>::Simulator(ParameterHandler &              prm,
                            const std::vector<std::string> &material_names,
                            const std::vector<std::string> &body_names,
                            const MPI_Comm                  communicator,
                            const bool                      restart)
    : communicator(communicator)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
    // Not bound to the communicator: a run that stops with an error must not
    // wait for the other ranks in the destructor. run() prints the
    // statistics over all ranks.
    , timer(pcout, TimerOutput::never, TimerOutput::wall_times)
    // mpirun gives its processes a pseudo-terminal even when its own output
    // goes to a file (a cluster job's log), so there progress is printed as
    // lines, which read well in a file.
    , progress_in_place(isatty(STDOUT_FILENO) &&
                        std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr &&
                        std::getenv("PMI_SIZE") == nullptr)
  {
    TimerOutput::Scope timer_section(timer, "setup");

    gravity = parse_point<dim>(prm.get("Gravity"), "Gravity");
    const std::string method = prm.get("Method");

    prm.enter_subsection("Time stepping");
    end_time        = prm.get_double("End time");
    fixed_time_step = prm.get_double("Time step");
    cfl_number      = prm.get_double("CFL number");
    n_load_steps    = prm.get_integer("Load steps");
    const std::string scheme_name = prm.get("Scheme");
    const typename ExplicitIntegrator<dim>::Scheme scheme =
      ExplicitIntegrator<dim>::parse_scheme(prm.get("Update scheme"));
    const double pic_fraction = prm.get_double("PIC fraction");
    prm.leave_subsection();
    if (!(end_time > 0.))
      throw InputError("Time stepping/End time must be positive.");
    if (!(cfl_number > 0.))
      throw InputError("Time stepping/CFL number must be positive.");

    prm.enter_subsection("Output");
    output_directory     = prm.get("Directory");
    write_paraview       = prm.get_bool("Write ParaView output");
    output_interval      = prm.get_double("Interval");
    write_grid           = prm.get_bool("Write grid");
    time_series_file     = prm.get("Time series file");
    time_series_interval = prm.get_double("Time series interval");
    tracked_positions =
      parse_point_list<dim>(prm.get("Tracked points"), "Output/Tracked points");
    prm.leave_subsection();

    prm.enter_subsection("Materials");
    for (const auto &name : material_names)
      {
        prm.enter_subsection(name);
        materials.push_back(
          Material::create(prm, name, "Materials/" + name));
        prm.leave_subsection();
      }
    prm.leave_subsection();

    prm.enter_subsection("Bodies");
    for (const auto &name : body_names)
      {
        prm.enter_subsection(name);
        bodies.emplace_back(prm, name, "Bodies/" + name, material_names);
        prm.leave_subsection();
      }
    prm.leave_subsection();

    grid      = std::make_unique<Grid<dim>>(prm, communicator);
    dirichlet = std::make_unique<DirichletConditions<dim>>(prm, *grid);
    if (dirichlet->has_contact() && scheme_name == "explicit")
      throw InputError("Boundary conditions/Contact boundaries are handled by "
                       "the quasi-static and Newmark schemes only; with Time "
                       "stepping/Scheme = explicit use Fixed or Slip "
                       "boundaries.");

    // Set up the grid and everything on it.
    grid->create();
    nodes = std::make_unique<GridNodes<dim>>(*grid);
    nodes->setup();
    basis = std::make_unique<GridBasis<dim>>(*grid);
    dirichlet->setup();

    // Every point carries as many internal variables as the largest law
    // needs, named after that law. Laws that share a variable keep it at
    // the same index (plastic_strain first), so every law's list must
    // start the longest one; the names in the output are then right for
    // every point.
    std::vector<std::string> internal_names;
    std::string              longest;
    for (const auto &m : materials)
      if (m->n_internal_variables() > internal_names.size())
        {
          internal_names = m->internal_variable_names();
          longest        = m->name();
        }
    for (const auto &m : materials)
      {
        const std::vector<std::string> &names = m->internal_variable_names();
        if (!std::equal(names.begin(), names.end(), internal_names.begin()))
          throw InputError("Materials '" + m->name() + "' (" +
                           comma_separated(names) + ") and '" + longest + "' (" +
                           comma_separated(internal_names) +
                           ") keep different internal variables, so one "
                           "scene cannot hold both: the point output would "
                           "name them wrongly.");
      }
    points = std::make_unique<MaterialPoints<dim>>(grid->get_triangulation(),
                                                   grid->get_mapping(),
                                                   internal_names,
                                                   scheme_name != "explicit");
    seeder = std::make_unique<PointSeeder<dim>>(*grid);
    seeder->seed(bodies, materials, *points);
    seeder->apply_geostatic_stress(bodies, materials, gravity, *points);
    loads = std::make_unique<PointLoads<dim>>(prm,
                                              scheme_name == "quasi-static",
                                              end_time);
    if (loads->is_active() && scheme_name == "explicit")
      throw InputError("Loads/Total force and Loads/Traction are applied by "
                       "the quasi-static and Newmark schemes only; Time "
                       "stepping/Scheme = explicit would ignore them.");
    loads->apply(*points);
    if (points->n_global_points() == 0)
      throw InputError("No body has a material point inside the grid: check "
                       "the shapes in Bodies against Grid/Arguments.");

    transfer = std::make_unique<GridTransfer<dim>>(
      *points, *basis, *nodes, *dirichlet, gravity);
    integrator = std::make_unique<ExplicitIntegrator<dim>>(
      *transfer, materials, scheme, pic_fraction, grid->minimum_cell_size(),
      timer);
    std::unique_ptr<MeshfreeBasis<dim>> meshfree;
    if (method != "MPM")
      {
        if (scheme_name == "explicit")
          throw InputError("Method = " + method + " runs with Time "
                           "stepping/Scheme = quasi-static or Newmark; the "
                           "explicit scheme is MPM only.");
        // The cloud's supports cross rank boundaries freely; ghost nodes
        // for them are not built yet (doc/architecture.md).
        if (Utilities::MPI::n_mpi_processes(communicator) > 1)
          throw InputError("Method = " + method + " runs on one rank only; "
                           "run this scene without mpirun, or with "
                           "Method = MPM.");
        meshfree = std::make_unique<MeshfreeBasis<dim>>(
          MeshfreeBasis<dim>::parse_parameters(
            prm,
            method == "GMM-MLS" ? MeshfreeBasis<dim>::Kind::mls :
                                  MeshfreeBasis<dim>::Kind::lme,
            grid->minimum_cell_size()));
      }
    if (scheme_name != "explicit")
      implicit = std::make_unique<ImplicitIntegrator<dim>>(scheme_name ==
                                                             "Newmark",
                                                           prm,
                                                           *points,
                                                           *grid,
                                                           *basis,
                                                           *dirichlet,
                                                           materials,
                                                           gravity,
                                                           pcout,
                                                           timer,
                                                           std::move(meshfree));
    dynamic_implicit = scheme_name == "Newmark";
    if (dynamic_implicit && !(fixed_time_step > 0.))
      throw InputError("Time stepping/Scheme = Newmark needs a Time step "
                       "above 0.");

    std::error_code error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::filesystem::create_directories(output_directory, error);
    if (Utilities::MPI::max(error ? 1 : 0, communicator) != 0)
      throw InputError("Output/Directory = '" + output_directory +
                       "' cannot be created.");
    vtu_output = std::make_unique<VtuOutput<dim>>(output_directory,
                                                  write_grid,
                                                  communicator);
    time_series = std::make_unique<TimeSeries<dim>>(
      output_directory + "/" + time_series_file, tracked_positions, gravity,
      *points, restart);
    // A continued run may go on further, or with smaller steps (after a
    // run that went unstable). The quasi-static loads ramp over End time,
    // so there only the number of load steps may change. The tangent
    // check only prints (and checkpoints from before it lack the entry).
    std::vector<std::string> entries_that_may_change = {
      "Output/Directory", "Newton/Check tangent"};
    if (!implicit)
      entries_that_may_change.insert(entries_that_may_change.end(),
                                     {"Time stepping/End time",
                                      "Time stepping/Time step",
                                      "Time stepping/CFL number"});
    else if (dynamic_implicit)
      entries_that_may_change.insert(entries_that_may_change.end(),
                                     {"Time stepping/End time",
                                      "Time stepping/Time step"});
    else
      entries_that_may_change.push_back("Time stepping/Load steps");
    checkpoint = std::make_unique<Checkpoint>(prm,
                                              output_directory,
                                              entries_that_may_change,
                                              communicator);

    next_output        = output_interval;
    next_time_series   = time_series_interval;
    next_implicit_step = implicit_step_size();
    if (!restart)
      checkpoint->discard_previous();
    else
      {
        checkpoint->read(
          [&](boost::archive::binary_iarchive &archive) {
            serialize(archive, 0);
          });
        // The step size may have been lowered.
        next_implicit_step = std::min(next_implicit_step, implicit_step_size());
        restarted = true;
      }

    // A fixed time step must be stable for the state the run starts from.
    if (fixed_time_step > 0. && !implicit)
      {
        const double limit = stability_limit(current_speeds());
        if (fixed_time_step > limit)
          throw InputError(fixed_step_beyond(limit) +
                           ". Use a smaller step, or 0 for an automatic one.");
      }
  }



  template <int dim>
  typename Simulator<dim>::Speeds
  Simulator<dim>::current_speeds() const
  {
    using Layout = PointLayout<dim>;
    Speeds speeds;
    for (const auto &particle : points->handler())
      {
        const ArrayView<const double> p = particle.get_properties();
        const Material &              material =
          *materials[static_cast<unsigned int>(p[Layout::material_id])];
        speeds.point = std::max(speeds.point, Layout::get_velocity(p).norm());
        speeds.signal =
          std::max(speeds.signal,
                   material.signal_speed(
                     Layout::get_stress(p),
                     ArrayView<const double>(&p[Layout::internal_variables],
                                             material.n_internal_variables()),
                     grid->minimum_cell_size()));
      }
    speeds.point  = Utilities::MPI::max(speeds.point, communicator);
    speeds.signal = Utilities::MPI::max(speeds.signal, communicator);
    return speeds;
  }



  template <int dim>
  double
  Simulator<dim>::stability_limit(const Speeds &speeds) const
  {
    return grid->minimum_cell_size() / (speeds.signal + speeds.point);
  }



  template <int dim>
  double
  Simulator<dim>::stable_time_step(const Speeds &speeds) const
  {
    const double step = cfl_number * stability_limit(speeds);
    // Every rank has the same speeds, so every rank throws.
    if (!(step > 0. && std::isfinite(step)))
      throw RunError("The explicit time step is not defined: the largest "
                     "signal speed is " + std::to_string(speeds.signal) +
                     " m/s and the fastest point moves at " +
                     std::to_string(speeds.point) +
                     " m/s (every point has come apart and rests, or a law "
                     "overflowed).");
    return step;
  }



  template <int dim>
  std::string
  Simulator<dim>::fixed_step_beyond(const double limit) const
  {
    std::ostringstream message;
    message << "Time stepping/Time step = " << fixed_time_step
            << " exceeds the explicit stability limit " << limit
            << " (smallest cell edge " << grid->minimum_cell_size()
            << " over the largest signal speed plus the fastest point)";
    return message.str();
  }



  template <int dim>
  void
  Simulator<dim>::check_step(
    const typename ExplicitIntegrator<dim>::StepReport &report,
    const double                                         step_size)
  {
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
                << time + step_size << ", dt = " << step_size
                << "): " << reason
                << ", at " << where
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
        message << "In step " << step + 1 << " (t = " << time + step_size
                << ", dt = " << step_size << ") the material point at "
                << where << " would move " << max_fraction
                << " cell widths, more than the one cell a step allows. "
                   "Reduce Time stepping/Time step or CFL number.";
        throw RunError(message.str());
      }
  }



  template <int dim>
  std::string
  Simulator<dim>::restart_hint() const
  {
    if (std::isnan(last_checkpoint_time))
      return "";
    std::ostringstream hint;
    hint << " The last checkpoint was saved at t = " << last_checkpoint_time
         << ": mpm --restart continues from it, with other step entries if "
            "they are what failed.";
    return hint.str();
  }



  template <int dim>
  double
  Simulator<dim>::implicit_step_size() const
  {
    return dynamic_implicit ? fixed_time_step : end_time / n_load_steps;
  }



  template <int dim>
  void
  Simulator<dim>::report_progress(const bool force)
  {
    if (Utilities::MPI::this_mpi_process(communicator) != 0)
      return;
    const double wall = wall_clock.wall_time();
    const double eta  = time > start_time ?
                          wall * (end_time - time) / (time - start_time) :
                          0.;
    std::ostringstream line;
    line << "step " << step << "  t = " << std::setprecision(4) << time
         << " / " << end_time << "  dt = " << std::setprecision(3) << dt
         << "  wall " << std::fixed << std::setprecision(1) << wall
         << " s  ETA " << eta << " s";
    if (progress_in_place)
      {
        if (force || wall - last_progress_wall > 0.25)
          {
            std::cout << '\r' << line.str() << "   " << (force ? "\n" : "")
                      << std::flush;
            last_progress_wall = wall;
          }
      }
    else
      {
        const unsigned int decile =
          static_cast<unsigned int>(10. * time / end_time + 1e-9);
        if (decile > last_progress_decile || force)
          {
            std::cout << line.str() << std::endl;
            last_progress_decile = decile;
          }
      }
  }



  template <int dim>
  typename Simulator<dim>::Speeds
  Simulator<dim>::explicit_step()
  {
    transfer->set_load_factor(loads->load_factor(time));
    const auto report = integrator->step(dt);
    check_step(report, dt);
    Speeds speeds;
    speeds.point  = Utilities::MPI::max(report.max_speed, communicator);
    speeds.signal = Utilities::MPI::max(report.max_signal_speed, communicator);
    const bool last_step = time + dt >= end_time - end_time_tolerance();
    if (fixed_time_step > 0. && !last_step)
      {
        const double limit = stability_limit(speeds);
        if (fixed_time_step > limit)
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
    return speeds;
  }



  template <int dim>
  void
  Simulator<dim>::implicit_step()
  {
    const unsigned int max_cuts = 4;
    for (unsigned int cut = 0;; ++cut)
      {
        try
          {
            const double load_factor = loads->load_factor(time + dt);
            if (dynamic_implicit)
              pcout << "  time step " << step + 1 << ": t = " << time + dt;
            else
              pcout << "  load step " << step + 1 << ": t = " << time + dt;
            pcout << ", load factor " << load_factor << std::endl;
            implicit->step(load_factor, dt);
            return;
          }
        catch (const RunError &e)
          {
            if (!e.smaller_step_helps)
              throw RunError(std::string(e.what()) +
                             " The last good state is in the output written "
                             "so far.",
                             false);
            if (cut == max_cuts)
              throw RunError(std::string(e.what()) + " Cut " +
                             std::to_string(max_cuts) +
                             " times; giving up. The last good state is in "
                             "the output written so far.");
            dt /= 2.;
            pcout << "  " << e.what() << " Cutting the step to " << dt << "."
                  << std::endl;
          }
      }
  }



  template <int dim>
  template <class Archive>
  void
  Simulator<dim>::serialize(Archive &archive, const unsigned int)
  {
    archive &time &step &dt &speeds.point &speeds.signal &next_output
      &next_time_series &next_implicit_step;
    archive &*points &*seeder &*vtu_output &*time_series;
    if (implicit)
      archive &*implicit;
  }



  template <int dim>
  void
  Simulator<dim>::run()
  {
    pcout << "mpm: " << dim << "D, " << grid->get_triangulation().n_global_active_cells()
          << " cells, " << points->n_global_points() << " material points, "
          << Utilities::MPI::n_mpi_processes(communicator) << " rank(s)"
          << std::endl;
    wall_clock.restart();
    start_time = time;
    start_step = step;
    if (restarted)
      {
        last_checkpoint_time = time;
        pcout << "mpm: continuing from the checkpoint at t = " << time
              << ", step " << step << std::endl
              << (checkpoint->enabled() ?
                    "" :
                    "mpm: note: Checkpoint/Wall time interval is 0, so this "
                    "part writes no checkpoint; a later --restart would go "
                    "back to the one it started from.\n");
      }
    else
      speeds = current_speeds();

    if (dynamic_implicit && !restarted)
      {
        // Newmark needs the initial acceleration: M a = f_ext - f_int with
        // the lumped mass, from the same projection the explicit scheme
        // uses.
        transfer->set_load_factor(loads->load_factor(0.));
        transfer->project_mass_momentum(true);
        transfer->compute_nodal_acceleration(0., false);
        transfer->for_each_point(
          [&](auto &particle, const Support<dim> &support) {
            const Tensor<1, dim> a = transfer->interpolate(
              support, GridNodes<dim>::NodalLayout::force);
            for (unsigned int d = 0; d < dim; ++d)
              particle->get_properties()[points->acceleration_index() + d] =
                a[d];
          });
      }
    if (!restarted)
      {
        TimerOutput::Scope t(timer, "output");
        // The nodal values are written as they were last projected; project
        // once so the first snapshot shows the initial grid state.
        transfer->project_mass_momentum(false);
        transfer->compute_nodal_velocity();
        diagnostics = time_series->write_row(time, step, 0., *points);
        if (write_paraview)
          vtu_output->write(time,
                            *points,
                            *nodes,
                            grid->get_mapping(),
                            implicit ? implicit->node_cloud() : nullptr);
      }
    const double time_tolerance = end_time_tolerance();

    // Only a step that overshoots End time is shortened: one that ends
    // within round-off of it keeps its size, so that a run which stops
    // there takes the same steps as one that goes on (a run continued from
    // its checkpoint repeats the uninterrupted run to the last bit).
    while (time < end_time - time_tolerance)
      {
        if (implicit)
          {
            dt = next_implicit_step;
            if (time + dt > end_time + time_tolerance)
              dt = end_time - time;
            implicit_step();
            next_implicit_step = std::min(implicit_step_size(), 2. * dt);
          }
        else
          {
            dt = (fixed_time_step > 0. ? fixed_time_step :
                                         stable_time_step(speeds));
            if (time + dt > end_time + time_tolerance)
              dt = end_time - time;
            speeds = explicit_step();
          }
        {
          TimerOutput::Scope t(timer, "sort points");
          points->sort();
        }
        time += dt;
        ++step;

        const bool at_end = !(time < end_time - time_tolerance);
        if (at_end || time_series_interval == 0. ||
            time >= next_time_series - time_tolerance)
          {
            TimerOutput::Scope t(timer, "time series");
            diagnostics = time_series->write_row(time, step, dt, *points);
            while (time_series_interval > 0. &&
                   next_time_series <= time + time_tolerance)
              next_time_series += time_series_interval;
          }
        if (write_paraview &&
            ((output_interval > 0. && time >= next_output - time_tolerance) ||
             at_end))
          {
            TimerOutput::Scope t(timer, "output");
            if (implicit)
              {
                // The implicit schemes do not use the nodal vector; project
                // for the grid output.
                transfer->project_mass_momentum(false);
                transfer->compute_nodal_velocity();
              }
            vtu_output->write(time,
                              *points,
                              *nodes,
                              grid->get_mapping(),
                              implicit ? implicit->node_cloud() : nullptr);
            while (output_interval > 0. &&
                   next_output <= time + time_tolerance)
              next_output += output_interval;
          }
        report_progress(at_end);
        const double wall = wall_clock.wall_time();
        if (checkpoint->enabled() && (at_end || checkpoint->due(wall)))
          {
            TimerOutput::Scope t(timer, "checkpoint");
            checkpoint->write(wall,
                              [&](boost::archive::binary_oarchive &archive) {
                                serialize(archive, 0);
                              });
            last_checkpoint_time = time;
            if (!at_end && checkpoint->stop_due(wall))
              {
                pcout << "mpm: stopped at t = " << time << " after "
                      << wall / 60. << " min (Checkpoint/Stop after); "
                      << "continue with --restart." << std::endl;
                break;
              }
          }
      }

    const double wall = wall_clock.wall_time();
    rusage       usage;
    getrusage(RUSAGE_SELF, &usage);
    const double peak_memory_mb =
      Utilities::MPI::sum(usage.ru_maxrss / 1024., communicator);
    // A continued run reports the steps it took itself.
    const unsigned int steps_taken = step - start_step;
    pcout << "mpm: " << steps_taken << " steps, "
          << static_cast<double>(points->n_global_points()) * steps_taken /
               wall /
               Utilities::MPI::n_mpi_processes(communicator)
          << " particle-steps per second per rank, " << wall
          << " s wall time, peak memory " << peak_memory_mb
          << " MB (all ranks)" << std::endl;
    if (implicit && implicit->meshfree_basis())
      {
        const auto &counts = implicit->meshfree_basis()->statistics();
        pcout << "meshfree: " << implicit->node_cloud()->size() << " nodes, "
              << counts.evaluations << " shape-function evaluations, "
              << counts.radius_growths
              << " of them with a larger radius (nodes added), "
              << counts.retries << " retries" << std::endl;
      }
    timer.print_wall_time_statistics(communicator);
  }



  template class Simulator<2>;
  template class Simulator<3>;
} // namespace mpm
