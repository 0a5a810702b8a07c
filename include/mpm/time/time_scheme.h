#ifndef mpm_time_time_scheme_h
#define mpm_time_time_scheme_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>

#include <mpm/assembly/grid_transfer.h>
#include <mpm/basis/node_cloud.h>
#include <mpm/boundary/point_loads.h>
#include <mpm/grid/grid.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * How a run advances in time: explicit MPM (ExplicitScheme), or the
   * quasi-static and Newmark schemes solved by Newton (ImplicitScheme). The
   * simulator builds the one the scene names, and its loop only asks it for
   * the next step; everything that depends on the scheme (the step size and
   * its checks, cut steps, the initial acceleration, what a continued run
   * may change) is the scheme's.
   */
  template <int dim>
  class TimeScheme
  {
  public:
    /** What every scheme works on; built by the simulator. */
    struct Scene
    {
      const Grid<dim> &                             grid;
      MaterialPoints<dim> &                         points;
      GridTransfer<dim> &                           transfer;
      const std::vector<const NodalCondition<dim> *> &nodal_conditions;
      const std::vector<std::unique_ptr<Material>> &materials;
      const PointLoads<dim> &                       loads;
      ConditionalOStream &                          pcout;
      TimerOutput &                                 timer;
    };

    /**
     * `Time stepping/Scheme`, `End time` and `Time step`; each scheme
     * declares its own entries.
     */
    static void
    declare_parameters(ParameterHandler &prm);

    /** The `Time stepping/Scheme` of a scene, before anything is built. */
    static std::string
    scheme_name(ParameterHandler &prm);

    /**
     * The point properties the scene's scheme needs, before the points are
     * built: the implicit schemes keep each point's acceleration and load
     * (the slots "acceleration" and "point_load").
     */
    static void
    request_point_slots(ParameterHandler &prm, PointSlots &slots);

    virtual ~TimeScheme() = default;

    /** Simulated time at which the run ends. */
    double
    end_time() const
    {
      return final_time;
    }

    /** Times closer than this to end_time() count as the end. */
    double
    end_time_tolerance() const
    {
      return 1e-12 * final_time;
    }

    /**
     * Bad input that only shows once the points exist (a fixed explicit
     * step beyond the stability limit) throws InputError.
     */
    virtual void
    check_start() const
    {}

    /** Before the first step of a fresh run (not of a continued one). */
    virtual void
    start()
    {}

    /**
     * The next step ends no later than t (the next release of an inflow),
     * as it ends at End time.
     */
    void
    end_next_step_by(const double t)
    {
      next_event = t;
    }

    /** Points were added (an inflow) before the next step. */
    virtual void
    points_added()
    {}

    /**
     * Take step number `step` + 1 from `time`, shortened only if it would
     * overshoot End time, and move the points (not yet re-sorted). Returns
     * the size of the step. A run that cannot go on throws RunError.
     */
    virtual double
    advance(const double time, const unsigned int step) = 0;

    /**
     * Make the grid's nodal mass and velocity current for the grid output;
     * the explicit scheme has them from its step.
     */
    virtual void
    prepare_grid_output()
    {}

    /** The node cloud of the meshfree method, or nullptr. */
    virtual const NodeCloud<dim> *
    node_cloud() const
    {
      return nullptr;
    }

    /** Closing lines of a run (the meshfree counts), on rank 0. */
    virtual void
    print_statistics() const
    {}

    /**
     * The entries of the scene that a run continued from a checkpoint may
     * change: the step entries of this scheme.
     */
    virtual std::vector<std::string>
    entries_that_may_change() const = 0;

    /** The state carried from step to step, for Checkpoint. */
    virtual void
    save(boost::archive::binary_oarchive &archive) const = 0;

    virtual void
    load(boost::archive::binary_iarchive &archive) = 0;

  protected:
    /**
     * A step of size dt from `time`, shortened only if it would overshoot
     * End time: one that ends within round-off of it keeps its size, so
     * that a run which stops there takes the same steps as one that goes
     * on.
     */
    double
    step_to_end(const double time, const double dt) const
    {
      const double stop = std::min(final_time, next_event);
      return time + dt > stop + end_time_tolerance() ? stop - time : dt;
    }

    /** An entry of `Time stepping` (the handler is at top level). */
    static std::string
    time_stepping_entry(ParameterHandler &prm, const std::string &entry);

    static double
    time_stepping_number(ParameterHandler &prm, const std::string &entry);

    /** Reads End time and Time step. */
    TimeScheme(ParameterHandler &prm, const Scene &scene);

    Scene  scene;
    double final_time;
    /** Time stepping/Time step: 0 chooses the explicit step. */
    double fixed_time_step;
    double next_event = std::numeric_limits<double>::infinity();
  };
} // namespace mpm

#endif
