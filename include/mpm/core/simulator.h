#ifndef mpm_core_simulator_h
#define mpm_core_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>

#include <mpm/assembly/grid_nodes.h>
#include <mpm/assembly/grid_transfer.h>
#include <mpm/basis/grid_basis.h>
#include <mpm/bodies/body.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/boundary/friction_walls.h>
#include <mpm/boundary/point_loads.h>
#include <mpm/boundary/rigid_obstacles.h>
#include <mpm/core/checkpoint.h>
#include <mpm/core/named_sections.h>
#include <mpm/bodies/point_seeder.h>
#include <mpm/grid/grid.h>
#include <mpm/materials/material.h>
#include <mpm/materials/material_library.h>
#include <mpm/output/time_series.h>
#include <mpm/output/vtu_output.h>
#include <mpm/points/grid_adaptation.h>
#include <mpm/points/load_balance.h>
#include <mpm/points/material_points.h>
#include <mpm/time/time_scheme.h>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Owns everything a run needs (grid, points, materials, output, timers),
   * builds the time scheme the scene names and runs the time loop: a step
   * of the scheme, the sort of the points, the output that is due, a
   * checkpoint. A scene is described entirely by the ParameterHandler it is
   * built from.
   */
  template <int dim>
  class Simulator
  {
  public:
    /**
     * Declare every entry except `Dimension` and the `Names` lists, which
     * Application declares for its first pass.
     */
    static void
    declare_parameters(ParameterHandler &prm, const SceneNames &names);

    /**
     * Parse the scene and set everything up; bad input throws InputError.
     * `restart`: continue from the checkpoint in the output directory.
     */
    Simulator(ParameterHandler &prm,
              const SceneNames &names,
              const MPI_Comm    communicator,
              const bool        restart = false);

    /** Run to the end time. A run that cannot go on throws RunError. */
    void
    run();

    /**
     * For the message of a run that cannot go on: where its last
     * checkpoint is and how to continue from it; empty if it has none.
     */
    std::string
    restart_hint() const;

    /** The diagnostics of the last time-series row. */
    const Diagnostics<dim> &
    last_diagnostics() const
    {
      return diagnostics;
    }

    const MaterialPoints<dim> &
    get_points() const
    {
      return *points;
    }

  private:
    /**
     * The state of the run, for Checkpoint: the loop's schedule here, and
     * each part's own state from the part. What the scene fixes is checked
     * on loading, so that a changed scene is refused, not misread.
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int);

    /** Times closer than this to End time count as the end. */
    double
    end_time_tolerance() const
    {
      return scheme->end_time_tolerance();
    }

    void
    report_progress(const bool force);

    /**
     * The output of the current state: points, grid (and the node cloud)
     * for ParaView, if written, and the walls' tractions.
     */
    void
    write_snapshot();

    const MPI_Comm     communicator;
    ConditionalOStream pcout;
    TimerOutput        timer;
    /** Progress rewrites one line on a terminal; else a line per 10 %. */
    const bool         progress_in_place;

    std::unique_ptr<Grid<dim>>                grid;
    std::unique_ptr<GridNodes<dim>>           nodes;
    std::unique_ptr<GridBasis<dim>>           basis;
    std::unique_ptr<DirichletConditions<dim>> dirichlet;
    std::unique_ptr<FrictionWalls<dim>>       friction_walls;
    std::unique_ptr<RigidObstacles<dim>>      obstacles;
    std::unique_ptr<FieldContact<dim>>        field_contact;
    std::string                               output_directory;
    /** Everything that acts at the grid's nodes, in the order it acts. */
    std::vector<const NodalCondition<dim> *>  nodal_conditions;
    /** The conditions and the contact between bodies, if any. */
    std::vector<const ForceReport *>          force_reports;
    std::unique_ptr<MaterialLibrary>          material_library;
    std::vector<Body<dim>>                    bodies;
    std::unique_ptr<MaterialPoints<dim>>      points;
    std::unique_ptr<PointSeeder<dim>>         seeder;
    std::unique_ptr<PointLoads<dim>>          loads;
    std::unique_ptr<GridTransfer<dim>>        transfer;
    std::unique_ptr<TimeScheme<dim>>          scheme;
    std::unique_ptr<VtuOutput<dim>>           vtu_output;
    std::unique_ptr<TimeSeries<dim>>          time_series;
    std::unique_ptr<Checkpoint>               checkpoint;
    std::unique_ptr<LoadBalance<dim>>         load_balance;
    std::unique_ptr<GridAdaptation<dim>>      adaptation;
    bool                                      restarted = false;

    Tensor<1, dim> gravity;
    double         end_time;

    double           time     = 0.;
    unsigned int     step     = 0;
    double           dt       = 0.;
    double           next_output      = 0.;
    double           next_time_series = 0.;
    Diagnostics<dim> diagnostics;
    Timer            wall_clock;
    double           last_progress_wall = 0.;
    /** Time of the last checkpoint written or read; NaN if none. */
    double last_checkpoint_time = std::numeric_limits<double>::quiet_NaN();
    /** Time and step this run started from (those of a checkpoint). */
    double           start_time = 0.;
    unsigned int     start_step = 0;
    /** Points times steps in this part of the run (an inflow adds points). */
    double           particle_steps = 0.;
    unsigned int     last_progress_decile = 0;
  };
} // namespace mpm

#endif
