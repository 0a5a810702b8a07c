#ifndef mpm_boundary_friction_walls_h
#define mpm_boundary_friction_walls_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/base/scene_choices.h>
#include <mpm/boundary/rigid_contact.h>
#include <mpm/grid/grid.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Rigid walls with Coulomb friction on named boundaries of the grid
   * ([W] 3.2, eq. 10). A wall holds the material only while it presses
   * (unilateral: a body may lift off) and resists sliding up to mu times
   * the normal force.
   *
   * In the explicit schemes the law acts at the wall's nodes
   * (CoulombContact), on the velocity the node would reach without the
   * wall. In the implicit schemes the system's active set finds the nodes
   * the walls hold, and whether each sticks or slides (ContactActiveSet);
   * the walls give it their normals, coefficients and constraints.
   * A node on several walls (a corner) meets each wall's law in turn. The
   * coefficient `0` gives a frictionless unilateral wall and `inf` one on
   * which the material cannot slide while it presses.
   *
   * The forces on each wall are measured at every nodal solve: their total
   * along and across the wall goes into the time series, and the nodal
   * tractions (force over the node's share of the wall) along the wall
   * into a CSV file at each output time.
   */
  template <int dim>
  class FrictionWalls : public RigidContact<dim>
  {
  public:
    /** `Boundary conditions/Friction boundaries`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Parse `Boundary conditions` (the handler is at top level). Connects
     * to Grid::changed, which calls setup().
     */
    FrictionWalls(ParameterHandler &prm, const Grid<dim> &grid);

    /** Whether the scene names any friction wall. */
    bool
    empty() const
    {
      return walls.empty();
    }

    /** Whether some wall is given an end time ('until'). */
    bool
    has_end_times() const
    {
      for (const Wall &wall : walls)
        if (wall.until < std::numeric_limits<double>::infinity())
          return true;
      return false;
    }

    /**
     * Walls that end need the explicit scheme; friction walls act with MPM
     * (InputError).
     */
    void
    check_scene(const SceneChoices &choices) const
    {
      if (has_end_times() && !choices.explicit_steps())
        throw InputError("Boundary conditions: a wall that ends ('name until "
                         "t') needs Time stepping/Scheme = explicit.");
      if (!empty() && choices.meshfree())
        throw InputError("Boundary conditions/Friction boundaries act with "
                         "Method = MPM; the meshfree methods take Fixed, "
                         "Slip and Contact boundaries.");
    }

    /** Find each wall's nodes, their normals and their shares of it. */
    void
    setup() override;

    /** Every wall holds the material only while it presses. */
    bool
    has_unilateral_nodes() const override
    {
      return !walls.empty();
    }

    bool
    acts_on(const unsigned int node) const override
    {
      return first_contact[node + 1] > first_contact[node];
    }

    /** Remove motion into the walls. */
    void
    constrain_velocity(const unsigned int node,
                       double *           velocity) const override;

    /**
     * Remove the acceleration into the walls, except where the node moves
     * away from the wall (a body thrown off it); friction is left to the
     * first step's solve.
     */
    void
    constrain_initial_acceleration(
      const unsigned int node,
      const double *     velocity,
      double *           acceleration) const override;

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

    /**
     * The blended mass's change at a node of a wall that stood in this
     * solve: each wall's Coulomb law again, from the velocity the node
     * would reach with the change (CoulombContact::follow_change), so that
     * the reported force, and the stick or slip, are those of the
     * corrected motion. A sticking node stays put while the change keeps
     * it inside the friction cone, a sliding one takes the change along the
     * wall less the friction's answer to the change of the normal force.
     */
    void
    constrain_change(const unsigned int,
                     const unsigned int slot,
                     double *           change) const override
    {
      this->follow_change(slot, change);
    }

    /** The node's walls, in the order of the entry. */
    unsigned int
    n_unilateral_walls(const unsigned int node) const override
    {
      return first_contact[node + 1] - first_contact[node];
    }

    const Tensor<1, dim> &
    unilateral_normal(const unsigned int node,
                      const unsigned int k) const override
    {
      return contacts[first_contact[node] + k].outward;
    }

    double
    friction_coefficient(const unsigned int node,
                         const unsigned int k) const override
    {
      return walls[contacts[first_contact[node] + k].wall].friction;
    }

    /**
     * A sticking node: every component; a sliding one: the component
     * along the wall's normal (the Coulomb force along the wall is the
     * implicit system's).
     */
    bool
    add_constraints(const unsigned int                              node,
                    const std::array<types::global_dof_index, dim> &dofs,
                    const Hold *                                    holds,
                    AffineConstraints<double> &constraints) const override;

    void
    reset_reactions() const override
    {
      this->clear_reactions();
    }

    /** Split into the parts along the wall's normal and across it. */
    void
    record_reaction(const unsigned int    node,
                    const unsigned int    k,
                    const Tensor<1, dim> &force) const override
    {
      const unsigned int c = first_contact[node] + k;
      this->record(node, c, contacts[c].outward, force);
    }

    /** `<wall>_normal_force` and `<wall>_tangential_force` per wall. */
    std::vector<std::string>
    force_names() const override;

    /**
     * The total force of the material on each wall at the last nodal
     * solve, along the wall's mean outward normal (positive: the material
     * presses) and across it (2D: along the normal turned by +90 degrees;
     * 3D: the magnitude). Per unit thickness in 2D. Collective.
     */
    std::vector<double>
    forces() const override;

    /**
     * Write `<wall>_tractions_<step>.csv` into `directory` for each wall:
     * node position, normal and tangential traction (force over the node's
     * share of the wall; tangential as in forces(), per node). Collective;
     * rank 0 writes, rows sorted by position.
     */
    void
    write_tractions(const std::string &directory,
                    const unsigned int step) const override;

  private:
    struct Wall
    {
      std::string        name;
      types::boundary_id id;
      double             friction;
      /** The wall acts while the time is below this. */
      double until;
      /** Unit mean outward normal, over all ranks. */
      Tensor<1, dim> mean_normal;
    };

    /** One wall at one node. */
    struct Contact
    {
      unsigned int   wall;
      Tensor<1, dim> outward;
      /** The node's share of the wall: half its edges, a quarter of its
       * faces (3D). */
      double     area;
      Point<dim> position;
    };

    /** Per wall: the total force vector from owned nodes, on this rank. */
    std::vector<Tensor<1, dim>>
    local_wall_forces() const;

    /** The direction of the tangential component in 2D. */
    static Tensor<1, dim>
    tangent_of(const Tensor<1, dim> &normal);

    using RigidContact<dim>::grid;
    std::vector<Wall> walls;

    /**
     * Contacts of node k: first_contact[k] to first_contact[k + 1]. A
     * contact is a surface of the reactions (RigidContact).
     */
    std::vector<unsigned int> first_contact;
    std::vector<Contact>      contacts;
    /** The start of the step of the last nodal solve. */
    mutable double solve_time = 0.;

    boost::signals2::scoped_connection grid_changed;
  };
} // namespace mpm

#endif
