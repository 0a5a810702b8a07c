#ifndef mpm_time_explicit_integrator_h
#define mpm_time_explicit_integrator_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/timer.h>

#include <mpm/assembly/grid_transfer.h>
#include <mpm/materials/material.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Explicit MPM time step with lumped mass, in one of three orders of
   * update:
   * - USF: stress from the projected velocity, then forces and motion.
   * - USL: forces from the old stress, motion, then stress from the new
   *   nodal velocity.
   * - MUSL (default), Wieckowski (2004) section 3.5, points 2-9: point
   *   velocities advanced with the nodal acceleration, projected once more
   *   to the grid (v^L), and stress and positions updated with v^L. This
   *   removes the division by near-zero nodal masses from the stress update.
   */
  template <int dim>
  class ExplicitIntegrator
  {
  public:
    enum class Scheme
    {
      USF,
      USL,
      MUSL
    };

    /** What one step saw, for the checks that follow it. */
    struct StepReport
    {
      double     max_speed         = 0.;
      double     max_cell_fraction = 0.;
      Point<dim> fastest_position;
      bool       failed = false;
      Point<dim> failed_position;
      std::string failure;
    };

    static Scheme
    parse_scheme(const std::string &name);

    ExplicitIntegrator(GridTransfer<dim> &                           transfer,
                       const std::vector<std::unique_ptr<Material>> &materials,
                       const Scheme                                  scheme,
                       TimerOutput &                                 timer);

    /** Advance all points by dt; the points are not yet re-sorted. */
    StepReport
    step(const double dt);

  private:
    using Layout      = PointLayout<dim>;
    using NodalLayout = typename GridNodes<dim>::NodalLayout;
    using Particle    = typename Particles::ParticleHandler<dim>::particle_iterator;

    /** V_p += dt a(x_p). */
    void
    advance_point_velocities(const double dt);

    /**
     * For every point: L from the nodal velocity, then F, stress and work
     * density; then, if `move`, x_p += dt v(x_p).
     */
    void
    update_points(const double dt, const bool move, StepReport &report);

    /** USL and USF: V_p += dt a(x_p) and x_p += dt v(x_p) in one pass. */
    void
    advance_and_move(const double dt, StepReport &report);

    void
    update_stress(Particle &            particle,
                  const Support<dim> &  support,
                  const double          dt,
                  StepReport &          report);

    void
    move(Particle &          particle,
         const Support<dim> &support,
         const double        dt,
         StepReport &        report);

    GridTransfer<dim> &                           transfer;
    const std::vector<std::unique_ptr<Material>> &materials;
    const Scheme                                  scheme;
    TimerOutput &                                 timer;
  };
} // namespace mpm

#endif
