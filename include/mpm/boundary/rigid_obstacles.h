#ifndef mpm_boundary_rigid_obstacles_h
#define mpm_boundary_rigid_obstacles_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
#include <mpm/base/shape.h>
#include <mpm/boundary/rigid_contact.h>
#include <mpm/grid/grid.h>

#include <memory>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Rigid obstacles inside the grid, in the explicit schemes: a footing, a
   * blade, a penetrometer or a ram. Each is a shape (box, disk, polygon;
   * box, sphere, cylinder in 3D) that stays put or moves by a prescribed
   * displacement u(t), with Coulomb friction against the material.
   *
   * An obstacle acts in the nodal solve on the grid nodes on or inside it
   * at the end of the step (signed distance <= 0 at x - u(t + dt)): on
   * the node's velocity relative to the obstacle's, (u(t + dt) - u(t)) /
   * dt, with the one Coulomb law of the walls (CoulombContact) and the
   * outward normal of the face the node comes through (contact_normal()).
   * The material presses the obstacle, slides along it or leaves it.
   *
   * The motion is given as a displacement, not a velocity: the position is
   * then exact at every step and needs no state, so a continued run
   * repeats an uninterrupted one. A constant velocity V is u = V t.
   */
  template <int dim>
  class RigidObstacles : public RigidContact<dim>
  {
  public:
    /** `Obstacles/<name>` for each name. */
    static void
    declare_parameters(ParameterHandler &              prm,
                       const std::vector<std::string> &names);

    /** Parse `Obstacles` (the handler is at top level). */
    RigidObstacles(ParameterHandler &              prm,
                   const std::vector<std::string> &names,
                   const Grid<dim> &               grid);

    bool
    empty() const
    {
      return obstacles.empty();
    }

    /** Obstacles act in the explicit scheme (InputError). */
    void
    check_scene(const SceneChoices &choices) const
    {
      if (!empty() && !choices.explicit_steps())
        throw InputError("Obstacles act in the explicit scheme (Time "
                         "stepping/Scheme = explicit); the quasi-static and "
                         "Newmark schemes take walls on the grid's "
                         "boundaries only.");
    }

    /**
     * On the first grid: check that each obstacle starts within a cell of
     * it. On every grid: place the obstacles where they stand at t = 0.
     */
    void
    setup() override;

    bool
    has_unilateral_nodes() const override
    {
      return false;
    }

    bool
    acts_on(const unsigned int node) const override;

    /** Remove motion into the obstacles, relative to theirs. */
    void
    constrain_velocity(const unsigned int node,
                       double *           velocity) const override;

    /**
     * The blended mass's change at a node in an obstacle: the obstacle's
     * Coulomb law again, from the velocity the node would reach with the
     * change (CoulombContact::follow_change).
     */
    void
    constrain_change(const unsigned int,
                     const unsigned int slot,
                     double *           change) const override
    {
      this->follow_change(slot, change);
    }

    /** Place the obstacles at t + dt, with their velocity over the step. */
    void
    begin_explicit_solve(const double time, const double dt) const override;

    void
    constrain_explicit(const unsigned int node,
                       const unsigned int slot,
                       const double       mass,
                       double *           velocity,
                       double *           acceleration,
                       const double       dt,
                       const double       time) const override;

    /** The implicit schemes refuse obstacles before they get here. */
    bool
    add_constraints(const unsigned int,
                    const std::array<types::global_dof_index, dim> &,
                    const Hold *,
                    AffineConstraints<double> &) const override
    {
      return false;
    }

    unsigned int
    n_unilateral_walls(const unsigned int) const override
    {
      return 0;
    }

    /**
     * Per obstacle: `<name>_force_x`, `_y` (, `_z`), the total force of
     * the material on it, then `<name>_normal_force` and
     * `<name>_tangential_force`, the sums over its nodes of the normal and
     * tangential force magnitudes.
     */
    std::vector<std::string>
    force_names() const override;

    std::vector<double>
    forces() const override;

    /**
     * `<name>_forces_<step>.csv` per obstacle: each node it acted on, its
     * position, normal and tangential force. Collective; rank 0 writes.
     */
    void
    write_tractions(const std::string &directory,
                    const unsigned int step) const override;

  private:
    struct Obstacle
    {
      std::string                        name;
      std::unique_ptr<Shape<dim>>        shape;
      std::unique_ptr<FunctionParser<1>> displacement;
      double                             friction;

      Tensor<1, dim>
      displacement_at(const double t) const;
    };

    /**
     * The outward normal of obstacle k that a node meets, moving with
     * `relative` velocity to it.
     */
    Tensor<1, dim>
    contact_normal(const unsigned int    k,
                   const unsigned int    node,
                   const Tensor<1, dim> &relative) const;

    /** Signed distance of a node to obstacle k in its current place. */
    double
    distance(const unsigned int k, const unsigned int node) const;

    using RigidContact<dim>::grid;
    /** Each is a surface of the reactions (RigidContact). */
    std::vector<Obstacle> obstacles;

    /** Per obstacle, set by begin_explicit_solve(). */
    mutable std::vector<Tensor<1, dim>> offsets;
    mutable std::vector<Tensor<1, dim>> velocities;

    /**
     * Whether setup() has checked the obstacles against a grid. An adaptive
     * grid coarsens where the material has left, so a later grid may hold
     * no node within its smallest cell of a small obstacle's start.
     */
    bool reach_checked = false;

    boost::signals2::scoped_connection grid_changed;
  };
} // namespace mpm

#endif
