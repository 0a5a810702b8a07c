#ifndef mpm_boundary_coulomb_contact_h
#define mpm_boundary_coulomb_contact_h

#include <deal.II/base/tensor.h>

namespace mpm
{
  using namespace dealii;

  /**
   * The Coulomb law of a rigid wall at one grid node ([W] 3.2, eq. 10), as
   * the m/dt limit of a penalty (Bardenhagen et al. 2000 for a rigid wall;
   * CB-Geo and Uintah act alike), written once for the grid's friction
   * walls and the rigid obstacles.
   *
   * `relative` is the node's velocity relative to the wall at the end of
   * the step, as it would be without the wall, and `into_wall` the unit
   * normal pointing out of the material into the wall. Where the node
   * moves into the wall (v_n = relative . into_wall > 0) the wall takes v_n
   * and the tangential part v_t either stops (stick: |v_t| <= mu v_n) or
   * loses mu v_n along itself (slip); elsewhere nothing happens. The
   * force of the material on the wall is m (relative - end) / dt: its
   * tangential part is at most mu times its normal part, and equal to it
   * where the node slips.
   */
  template <int dim>
  struct CoulombContact
  {
    /** Whether the node moves into the wall, so that the law acts. */
    bool           active = false;
    /** The relative velocity at the end of the step. */
    Tensor<1, dim> end;
    /** The force of the material on the wall along `into_wall`, >= 0. */
    double         normal_force = 0.;
    /** The rest of that force, across `into_wall`. */
    Tensor<1, dim> tangential_force;

    /** No contact. */
    CoulombContact() = default;

    CoulombContact(const Tensor<1, dim> &relative,
                   const Tensor<1, dim> &into_wall,
                   const double          friction,
                   const double          mass,
                   const double          dt)
      : end(relative)
      , relative(relative)
      , into_wall(into_wall)
      , friction(friction)
      , mass(mass)
      , dt(dt)
    {
      const double v_n = relative * into_wall;
      if (!(v_n > 0.))
        return;
      active                     = true;
      const Tensor<1, dim> v_t   = relative - v_n * into_wall;
      const double         slide = v_t.norm();
      const double         limit = friction * v_n;
      // Stick where the wall can stop the sliding, else slip against it.
      end = slide <= limit ? Tensor<1, dim>() : (1. - limit / slide) * v_t;
      normal_force     = mass * v_n / dt;
      tangential_force = mass * (v_t - end) / dt;
    }

    /** The force of the material on the wall, m (relative - end) / dt. */
    Tensor<1, dim>
    force() const
    {
      return mass * (relative - end) / dt;
    }

    /**
     * The blended mass changes the node's acceleration by `change` after
     * the nodal solve that gave this law: the same wall again, from the
     * relative velocity moved by dt change, so that its force and its
     * stick or slip follow the change (the wall lets the node go where it
     * no longer presses). `change` becomes what the node keeps of it,
     * (the new end - end) / dt.
     */
    CoulombContact
    follow_change(double *change) const
    {
      Tensor<1, dim> moved = relative;
      for (unsigned int d = 0; d < dim; ++d)
        moved[d] += dt * change[d];
      const CoulombContact law(moved, into_wall, friction, mass, dt);
      // A wall that acts neither before nor after leaves the change as it
      // is, not as the round-off of (moved - relative) / dt.
      if (active || law.active)
        for (unsigned int d = 0; d < dim; ++d)
          change[d] = (law.end[d] - end[d]) / dt;
      return law;
    }

  private:
    /** What the law was given, for follow_change(). */
    Tensor<1, dim> relative;
    Tensor<1, dim> into_wall;
    double         friction = 0.;
    double         mass     = 0.;
    double         dt       = 1.;
  };
} // namespace mpm

#endif
