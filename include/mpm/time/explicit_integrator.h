#ifndef mpm_time_explicit_integrator_h
#define mpm_time_explicit_integrator_h

#include <deal.II/base/point.h>
#include <deal.II/base/timer.h>

#include <mpm/assembly/grid_transfer.h>
#include <mpm/base/shared_position.h>
#include <mpm/materials/material.h>

#include <memory>
#include <string>
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
   *   to the grid (v^L), and stress and positions updated with v^L. The
   *   stress then sees the mass-weighted point velocities instead of f/m,
   *   which a node with a tiny mass turns into a spurious strain rate.
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
      double      max_speed         = 0.;
      /** The largest Material::signal_speed after the stress update. */
      double      max_signal_speed  = 0.;
      double      max_cell_fraction = 0.;
      Point<dim>  fastest_position;
      bool        failed = false;
      Point<dim>  failed_position;
      std::string failure;

      /**
       * Keep the failure of the lexicographically first point, so that the
       * message does not depend on the order or number of ranks.
       */
      void
      record_failure(const Point<dim> &position, const std::string &reason)
      {
        if (!failed || lexicographically_less(position, failed_position))
          {
            failed          = true;
            failed_position = position;
            failure         = reason;
          }
      }
    };

    static Scheme
    parse_scheme(const std::string &name);

    /**
     * `pic_fraction` is the share of the PIC velocity in the point velocity
     * update (0: pure FLIP). The grid's smallest cell edge, taken at the
     * start of each step, is how far a point may move in one (and sizes
     * the viscous limit of the signal speed).
     */
    ExplicitIntegrator(GridTransfer<dim> &                           transfer,
                       const std::vector<std::unique_ptr<Material>> &materials,
                       const Scheme                                  scheme,
                       const double                                  pic_fraction,
                       const bool average_dilatation,
                       const Grid<dim> &                             grid,
                       TimerOutput &                                 timer);

    /** Advance all points by dt; the points are not yet re-sorted. */
    StepReport
    step(const double dt);

  private:
    using Layout      = PointLayout<dim>;
    using NodalLayout = typename GridNodes<dim>::NodalLayout;
    using Particle = typename Particles::ParticleHandler<dim>::particle_iterator;

    /** What one grid-to-point pass does at every point, in this order. */
    struct PointUpdate
    {
      /** V_p += dt a(x_p), blended with the PIC velocity if asked. */
      bool advance_velocity = false;
      /** L from the nodal velocity, then F, stress and work density. */
      bool update_stress = false;
      /** x_p += dt v(x_p). */
      bool move = false;
    };

    /** One pass over the points, with each point's support evaluated once. */
    void
    update_points(const double       dt,
                  const PointUpdate &update,
                  StepReport &       report);

    /**
     * What must be known before any update_stress() of a pass: the grid
     * fields the laws read, solved; the cells' mean dilatation rates.
     */
    void
    prepare_stress_update();

    /** V_p += dt a(x_p), blended with the PIC velocity if asked. */
    void
    advance_velocity(Particle &particle, const Support<dim> &support, double dt)
      const;

    void
    update_stress(Particle &          particle,
                  const Support<dim> &support,
                  const double        dt,
                  StepReport &        report);

    /**
     * The 3x3 velocity gradient of a point: in an axisymmetric scene with
     * the hoop rate v_r / r, in plane strain with L_zz = 0 (in plane
     * stress the law chooses L_zz when the step is committed).
     */
    Tensor<2, 3>
    velocity_gradient(const Particle &particle, const Support<dim> &support)
      const;

    /**
     * Per cell that holds points, the volume-weighted mean of their
     * dilatation rates tr L, for the cell-average option.
     */
    void
    average_dilatation_rates();

    void
    move(Particle &          particle,
         const Support<dim> &support,
         const double        dt,
         StepReport &        report);

    GridTransfer<dim> &                           transfer;
    const std::vector<std::unique_ptr<Material>> &materials;
    const Scheme                                  scheme;
    const double                                  pic_fraction;
    const bool                                    average_dilatation;
    /** By active cell index: sum of V tr L, then their mean; and sum of V. */
    std::vector<double> cell_dilatation_rate, cell_volume;
    /** The cells that hold points, whose entries above are set. */
    std::vector<unsigned int> occupied_cells;
    const Grid<dim> &                             grid;
    /** The grid's smallest cell edge in this step. */
    double                                        cell_size = 0.;
    TimerOutput &                                 timer;
  };
} // namespace mpm

#endif
