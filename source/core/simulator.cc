#include <deal.II/base/mpi.h>

#include <mpm/base/input_error.h>
#include <mpm/base/parse.h>
#include <mpm/core/simulator.h>
#include <mpm/time/explicit_scheme.h>
#include <mpm/time/implicit_scheme.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  Simulator<dim>::declare_parameters(ParameterHandler &prm,
                                     const SceneNames &names)
  {
    prm.declare_entry("Gravity",
                      dim == 2 ? "0, 0" : "0, 0, 0",
                      Patterns::Anything(),
                      "Gravitational acceleration, one component per "
                      "dimension, e.g. '0, -9.81' [m/s^2].");

    prm.declare_entry(
      "Method", "MPM", Patterns::Selection("MPM|GMM-MLS|GMM-LME"),
      "MPM: the material point method, on the background grid's shape "
      "functions (Grid/Shape functions). GMM-MLS, GMM-LME: the Galerkin meshfree method (Iaconeta "
      "et al. 2017), on a cloud of nodes that starts at the grid vertices "
      "of the cells holding material and moves with it, with moving least "
      "squares or local max-entropy shape functions (see Meshfree). The "
      "meshfree methods run with the quasi-static and Newmark schemes.");
    MeshfreeBasis<dim>::declare_parameters(prm);
    Grid<dim>::declare_parameters(prm);
    GridBasis<dim>::declare_parameters(prm);
    DirichletConditions<dim>::declare_parameters(prm);
    FrictionWalls<dim>::declare_parameters(prm);
    MaterialPoints<dim>::declare_parameters(prm);
    PointLoads<dim>::declare_parameters(prm);
    TimeScheme<dim>::declare_parameters(prm);
    ExplicitScheme<dim>::declare_parameters(prm);
    ImplicitScheme<dim>::declare_parameters(prm);

    prm.enter_subsection("Output");
    prm.declare_entry("Directory", "output", Patterns::Anything(),
                      "Directory for all output; created if missing.");
    prm.leave_subsection();
    VtuOutput<dim>::declare_parameters(prm);
    TimeSeries<dim>::declare_parameters(prm);
    Checkpoint::declare_parameters(prm);
    LoadBalance<dim>::declare_parameters(prm);
    GridAdaptation<dim>::declare_parameters(prm);

    MaterialLibrary::declare_parameters(prm, names.materials);

    prm.enter_subsection("Bodies");
    for (const auto &name : names.bodies)
      {
        prm.enter_subsection(name);
        Body<dim>::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
    RigidObstacles<dim>::declare_parameters(prm, names.obstacles);
    FieldContact<dim>::declare_parameters(prm);
  }



  template <int dim>
  Simulator<dim>::Simulator(ParameterHandler &prm,
                            const SceneNames &names,
                            const MPI_Comm    communicator,
                            const bool        restart)
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
    const SceneChoices choices{TimeScheme<dim>::scheme_name(prm),
                               prm.get("Method")};
    // Checked first, before anything is built from them.
    prm.enter_subsection("Time stepping");
    end_time = prm.get_double("End time");
    const double cfl_number = prm.get_double("CFL number");
    prm.leave_subsection();
    if (!(end_time > 0.))
      throw InputError("Time stepping/End time must be positive.");
    if (!(cfl_number > 0.))
      throw InputError("Time stepping/CFL number must be positive.");
    prm.enter_subsection("Output");
    output_directory = prm.get("Directory");
    prm.leave_subsection();

    // Each part refuses what it cannot do with the scene's choices as soon
    // as it is read.
    material_library = std::make_unique<MaterialLibrary>(prm, names.materials);
    const std::vector<std::unique_ptr<Material>> &materials =
      material_library->laws();
    prm.enter_subsection("Bodies");
    for (const auto &name : names.bodies)
      {
        prm.enter_subsection(name);
        bodies.emplace_back(prm, name, "Bodies/" + name, names.materials);
        prm.leave_subsection();
        bodies.back().check_scene(choices);
      }
    prm.leave_subsection();
    material_library->check_scene(choices);

    grid      = std::make_unique<Grid<dim>>(prm, communicator);
    field_contact =
      std::make_unique<FieldContact<dim>>(prm, bodies, *grid);
    dirichlet = std::make_unique<DirichletConditions<dim>>(prm, *grid);
    dirichlet->check_scene(choices);
    friction_walls = std::make_unique<FrictionWalls<dim>>(prm, *grid);
    friction_walls->check_scene(choices);
    grid->geometry().check_gravity(gravity);
    material_library->check_geometry(grid->geometry());
    const GridShapeFunctions shape_functions =
      GridBasis<dim>::parse_kind(prm);
    GridBasis<dim>::check_scene(choices, shape_functions);
    field_contact->check_scene(choices);
    MeshfreeBasis<dim>::check_scene(choices, grid->geometry());
    obstacles =
      std::make_unique<RigidObstacles<dim>>(prm, names.obstacles, *grid);
    obstacles->check_scene(choices);

    // Set up the grid and everything on it (the conditions find their
    // nodes when the grid announces itself).
    grid->create();
    if (grid->geometry().kind() == Geometry<dim>::Kind::axisymmetric)
      dirichlet->check_axis();
    nodes = std::make_unique<GridNodes<dim>>(*grid, field_contact->n_groups());
    nodes->setup();
    basis = std::make_unique<GridBasis<dim>>(*grid, shape_functions);

    loads = std::make_unique<PointLoads<dim>>(prm,
                                              choices.quasi_static(),
                                              end_time);
    // Each part asks for the point properties it needs.
    PointSlots slots;
    TimeScheme<dim>::request_point_slots(prm, slots);
    loads->request_point_slots(slots);
    GridAdaptation<dim>::request_point_slots(prm, slots);
    points = std::make_unique<MaterialPoints<dim>>(
      *grid,
      material_library->internal_variable_names(),
      slots,
      !choices.explicit_steps());
    points->parse_outflow(prm);

    // A grid that follows the material is refined around the bodies before
    // they are seeded, so that the points fill the finest cells; the
    // inflows' regions stay refined for the whole run.
    const auto near_body = [](const Body<dim> &body, const auto &cell) {
      return body.region().reaches_cell(cell);
    };
    std::vector<bool> plastic_law;
    for (const auto &material : materials)
      plastic_law.push_back(material->n_internal_variables() > 0 &&
                            material->internal_variable_names()[0] ==
                              "plastic_strain");
    adaptation = std::make_unique<GridAdaptation<dim>>(
      prm,
      *grid,
      *points,
      [this, near_body](const auto &cell) {
        return std::any_of(bodies.begin(),
                           bodies.end(),
                           [&](const Body<dim> &body) {
                             return body.is_inflow() && near_body(body, cell);
                           });
      },
      plastic_law,
      pcout);
    adaptation->check_scene(choices,
                            shape_functions == GridShapeFunctions::linear);
    adaptation->refine_around([this, near_body](const auto &cell) {
      return std::any_of(bodies.begin(),
                         bodies.end(),
                         [&](const Body<dim> &body) {
                           return near_body(body, cell);
                         });
    });
    seeder = std::make_unique<PointSeeder<dim>>(*grid);
    seeder->check_bodies(bodies, materials);
    seeder->release_due(bodies, materials, *points, 0., 0.);
    seeder->apply_geostatic_stress(bodies, materials, gravity, *points);
    loads->apply(*points);
    const bool has_inflow =
      std::any_of(bodies.begin(), bodies.end(), [](const Body<dim> &body) {
        return body.is_inflow();
      });
    if (points->n_global_points() == 0 && !has_inflow)
      throw InputError("No body has a material point inside the grid: check "
                       "the shapes in Bodies against Grid/Arguments.");

    // Only what the scene uses: each node asks every condition in the list.
    nodal_conditions = {dirichlet.get()};
    if (!friction_walls->empty())
      nodal_conditions.push_back(friction_walls.get());
    if (!obstacles->empty())
      nodal_conditions.push_back(obstacles.get());
    transfer         = std::make_unique<GridTransfer<dim>>(
      *points,
      *basis,
      *nodes,
      nodal_conditions,
      gravity,
      field_contact->field_of_body());
    force_reports.assign(nodal_conditions.begin(), nodal_conditions.end());
    if (field_contact->n_groups() > 1)
      {
        transfer->couple_fields_by(*field_contact);
        force_reports.push_back(field_contact.get());
      }
    transfer->use_grid_fields(materials);
    const typename TimeScheme<dim>::Scene scene{*grid,
                                                *points,
                                                *transfer,
                                                nodal_conditions,
                                                materials,
                                                *loads,
                                                pcout,
                                                timer};
    if (choices.explicit_steps())
      {
        ExplicitScheme<dim>::check_scene(choices);
        scheme = std::make_unique<ExplicitScheme<dim>>(prm, scene);
      }
    else
      scheme = std::make_unique<ImplicitScheme<dim>>(
        prm,
        scene,
        choices.newmark(),
        *basis,
        *dirichlet,
        gravity,
        MeshfreeBasis<dim>::create(prm, choices, grid->minimum_cell_size()));

    std::error_code error;
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::filesystem::create_directories(output_directory, error);
    if (Utilities::MPI::max(error ? 1 : 0, communicator) != 0)
      throw InputError("Output/Directory = '" + output_directory +
                       "' cannot be created.");
    vtu_output =
      std::make_unique<VtuOutput<dim>>(prm,
                                       output_directory,
                                       end_time,
                                       communicator);
    time_series = std::make_unique<TimeSeries<dim>>(
      prm, output_directory, gravity, *points, force_reports, restart);
    // The tangent check only prints, and the explicit velocity projection
    // is made anew at every step (checkpoints from before either lack the
    // entry); the scheme's step entries may change too.
    std::vector<std::string> entries_that_may_change = {
      "Output/Directory",
      "Newton/Check tangent",
      "Time stepping/Velocity projection"};
    for (const std::string &entry : scheme->entries_that_may_change())
      entries_that_may_change.push_back(entry);
    for (const std::string &entry : LoadBalance<dim>::entries_that_may_change())
      entries_that_may_change.push_back(entry);
    load_balance = std::make_unique<LoadBalance<dim>>(
      prm, *grid, *points, output_directory, restart, pcout);
    checkpoint = std::make_unique<Checkpoint>(prm,
                                              output_directory,
                                              entries_that_may_change,
                                              communicator);

    next_output      = vtu_output->interval();
    next_time_series = time_series->interval();
    if (!restart)
      checkpoint->discard_previous();
    else
      {
        checkpoint->read(
          [&](boost::archive::binary_iarchive &archive) {
            serialize(archive, 0);
          });
        restarted = true;
      }
    scheme->check_start();
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
  template <class Archive>
  void
  Simulator<dim>::serialize(Archive &archive, const unsigned int)
  {
    archive &time &step &dt &next_output &next_time_series;
    // The cells and their partition before the points: they load into the
    // cells their rank owned.
    archive &*adaptation &*load_balance &*points &*seeder &*vtu_output
      &*time_series;
    if constexpr (Archive::is_saving::value)
      scheme->save(archive);
    else
      scheme->load(archive);
  }



  template <int dim>
  void
  Simulator<dim>::write_snapshot()
  {
    if (vtu_output->enabled())
      vtu_output->write(time,
                        *points,
                        *nodes,
                        grid->get_mapping(),
                        scheme->node_cloud());
    for (const ForceReport *report : force_reports)
      report->write_tractions(output_directory, step);
  }



  template <int dim>
  void
  Simulator<dim>::run()
  {
    pcout << "mpm: " << dim << "D, "
          << grid->get_triangulation().n_global_active_cells() << " cells, "
          << points->n_global_points() << " material points, "
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
      {
        scheme->start();
        TimerOutput::Scope t(timer, "output");
        // The nodal values are written as they were last projected; project
        // once so the first snapshot shows the initial grid state.
        transfer->project_mass_momentum(false);
        transfer->compute_nodal_velocity();
        diagnostics = time_series->write_row(time, step, 0., *points);
        write_snapshot();
      }
    const double time_tolerance   = end_time_tolerance();
    const double output_interval  = vtu_output->interval();
    const double series_interval  = time_series->interval();

    // Only a step that overshoots End time is shortened: one that ends
    // within round-off of it keeps its size, so that a run which stops
    // there takes the same steps as one that goes on (a run continued from
    // its checkpoint repeats the uninterrupted run to the last bit).
    while (time < end_time - time_tolerance)
      {
        {
          TimerOutput::Scope t(timer, "inflow");
          if (seeder->release_due(
                bodies,
                material_library->laws(),
                *points,
                time,
                time_tolerance))
            scheme->points_added();
          scheme->end_next_step_by(seeder->next_release_time(bodies));
        }
        // Between the step's outputs and the next step, and after the points
        // released now: a run continued from a checkpoint written at this
        // step makes the same check.
        {
          TimerOutput::Scope t(timer, "adaptive grid");
          if (adaptation->check(step, time))
            load_balance->grid_adapted();
        }
        {
          TimerOutput::Scope t(timer, "load balance");
          load_balance->check(time, step);
        }
        particle_steps += points->n_global_points();
        dt = scheme->advance(time, step);
        {
          TimerOutput::Scope t(timer, "sort points");
          points->sort();
        }
        time += dt;
        ++step;

        const bool at_end = !(time < end_time - time_tolerance);
        if (at_end || series_interval == 0. ||
            time >= next_time_series - time_tolerance)
          {
            TimerOutput::Scope t(timer, "time series");
            diagnostics = time_series->write_row(time, step, dt, *points);
            while (series_interval > 0. &&
                   next_time_series <= time + time_tolerance)
              next_time_series += series_interval;
          }
        if ((output_interval > 0. && time >= next_output - time_tolerance) ||
            at_end)
          {
            TimerOutput::Scope t(timer, "output");
            if (vtu_output->enabled())
              scheme->prepare_grid_output();
            write_snapshot();
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
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double peak_memory_mb =
      Utilities::MPI::sum(memory.VmHWM / 1024., communicator);
    const double end_memory_mb =
      Utilities::MPI::sum(memory.VmRSS / 1024., communicator);
    // A continued run reports the steps it took itself.
    const unsigned int steps_taken = step - start_step;
    pcout << "mpm: " << steps_taken << " steps, "
          << particle_steps / wall /
               Utilities::MPI::n_mpi_processes(communicator)
          << " particle-steps per second per rank, " << wall
          << " s wall time, peak memory " << peak_memory_mb
          << " MB (all ranks), " << end_memory_mb << " MB at the end"
          << std::endl;
    if (adaptation->enabled())
      pcout << "mpm: the grid adapted " << adaptation->n_adaptations()
            << " times; " << grid->get_triangulation().n_global_active_cells()
            << " cells at the end" << std::endl;
    scheme->print_statistics();
    timer.print_wall_time_statistics(communicator);
  }



  template class Simulator<2>;
  template class Simulator<3>;
} // namespace mpm
