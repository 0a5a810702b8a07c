#ifndef mpm_time_explicit_scheme_h
#define mpm_time_explicit_scheme_h

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
#include <mpm/time/explicit_integrator.h>
#include <mpm/time/time_scheme.h>

#include <limits>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Explicit MPM in time: each step's size from the CFL condition (or the
   * fixed Time step, checked against it), one ExplicitIntegrator step, and
   * the checks that stop a run which went unstable.
   */
  template <int dim>
  class ExplicitScheme : public TimeScheme<dim>
  {
  public:
    /** The explicit scheme is MPM only (InputError for a meshfree method). */
    static void
    check_scene(const SceneChoices &choices)
    {
      if (choices.meshfree())
        throw InputError("Method = " + choices.method + " runs with Time "
                         "stepping/Scheme = quasi-static or Newmark; the "
                         "explicit scheme is MPM only.");
    }

    /** `CFL number`, `Update scheme` and `PIC fraction`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * The entries of declare_parameters() that `prm` (at top level) sets to
     * other values than their defaults: what an implicit run ignores.
     */
    static std::vector<std::string>
    entries_set(ParameterHandler &prm);

    ExplicitScheme(ParameterHandler &                         prm,
                   const typename TimeScheme<dim>::Scene &scene);

    /** A fixed Time step must be stable for the state the run starts from. */
    void
    check_start() const override;

    void
    start() override;

    /** The next step also follows the speeds of the new points. */
    void
    points_added() override;

    double
    advance(const double time, const unsigned int step) override;

    std::vector<std::string>
    entries_that_may_change() const override;

    void
    save(boost::archive::binary_oarchive &archive) const override;

    void
    load(boost::archive::binary_iarchive &archive) override;

  private:
    /** The largest point speed and signal speed (Material::signal_speed). */
    struct Speeds
    {
      double point  = 0.;
      double signal = 0.;
    };

    /** Speeds of the points as they are, over all ranks. */
    Speeds
    current_speeds() const;

    /**
     * The smallest cell edge over the sum of the speeds: the largest stable
     * step (infinite if nothing moves or is stiff).
     */
    double
    stability_limit(const Speeds &speeds) const;

    /**
     * The CFL number times the stability limit; throws RunError if that is
     * not a positive number.
     */
    double
    stable_time_step(const Speeds &speeds) const;

    /** "Time stepping/Time step = ... exceeds the ... limit (why)". */
    std::string
    fixed_step_beyond(const double limit) const;

    /** Stop the run if a point failed or would skip a cell. */
    void
    check_step(const typename ExplicitIntegrator<dim>::StepReport &report,
               const double                                         time,
               const unsigned int                                   step,
               const double                                         dt) const;

    double                   cfl_number;
    ExplicitIntegrator<dim>  integrator;
    /** The speeds after the last step: they limit the next one. */
    Speeds                   speeds;
  };
} // namespace mpm

#endif
