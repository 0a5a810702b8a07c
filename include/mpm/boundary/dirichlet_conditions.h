#ifndef mpm_boundary_dirichlet_conditions_h
#define mpm_boundary_dirichlet_conditions_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/base/scene_choices.h>
#include <mpm/boundary/nodal_condition.h>
#include <mpm/grid/grid.h>

#include <algorithm>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Velocity conditions on named boundaries of the background grid:
   * `fixed` (zero velocity), `slip` (zero normal velocity) and `contact`
   * (zero velocity while the material presses on the wall, free where it
   * pulls away: unilateral contact without slip, which lets a body roll).
   * The faces of one boundary id form one wall, whose normal at a node is
   * the average of its faces' normals there, so a curved slip wall stays a
   * slip wall. A node where walls of different ids meet loses each wall's
   * normal component; a node on a fixed face is fixed, and otherwise a node
   * on a contact face is a contact node.
   *
   * A wall named 'name until t' acts while the time is below t (explicit
   * scheme): at the first nodal solve from t on, the nodes are found again
   * without it.
   */
  template <int dim>
  class DirichletConditions : public NodalCondition<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Parse the `Boundary conditions` subsection at top level; the names
     * are the grid's boundary names. Connects to Grid::changed, which
     * calls setup() (also when the grid is first created).
     */
    DirichletConditions(ParameterHandler &prm, const Grid<dim> &grid);

    /**
     * Contact walls need an implicit scheme, walls that end the explicit
     * one (InputError).
     */
    void
    check_scene(const SceneChoices &choices) const;

    /**
     * An axisymmetric grid's boundary on x = 0 must be held across the
     * axis for the whole run (a Slip or Fixed boundary without 'until');
     * the message says so if it is not. Collective.
     */
    void
    check_axis() const;

    /** Find the constrained nodes of all locally relevant cells. */
    void
    setup() override
    {
      find_nodes();
    }

    /** Find the nodes again if a wall has ended since the last time. */
    void
    begin_explicit_solve(const double time, const double dt) const override;

    /** Whether some wall is given an end time ('until'). */
    bool
    has_end_times() const
    {
      return !end_times.empty();
    }

    /** Whether the walls with this boundary id end during the run. */
    bool
    ends(const types::boundary_id id) const
    {
      return end_times.count(id) > 0;
    }

    bool
    has_unilateral_nodes() const override
    {
      return has_contact();
    }

    bool
    acts_on(const unsigned int node) const override
    {
      return constraint_of_node[node] >= 0;
    }

    void
    constrain_velocity(const unsigned int node,
                       double *           velocity) const override
    {
      apply(node, velocity);
    }

    void
    constrain_change(const unsigned int node,
                     const unsigned int,
                     double *change) const override
    {
      apply(node, change);
    }

    /** Constrain v and a alike, so that v + dt a is constrained. */
    void
    constrain_explicit(const unsigned int node,
                       const unsigned int,
                       const double,
                       double *velocity,
                       double *acceleration,
                       const double,
                       const double) const override
    {
      apply(node, acceleration);
      apply(node, velocity);
    }

    /**
     * A fixed or held contact node: every component; a contact node that
     * is not held keeps no slip along its wall; a slip node: the normal
     * component of each wall, fixed on a wall along an axis and tied to
     * the others on a slanted one (not at corners of slanted walls).
     */
    bool
    add_constraints(const unsigned int                              node,
                    const std::array<types::global_dof_index, dim> &dofs,
                    const Hold *                                    holds,
                    AffineConstraints<double> &constraints) const override;

    /** A contact node has one unilateral wall. */
    unsigned int
    n_unilateral_walls(const unsigned int node) const override
    {
      const Constraint *constraint = constraint_of(node);
      return constraint != nullptr && constraint->unilateral ? 1 : 0;
    }

    const Tensor<1, dim> &
    unilateral_normal(const unsigned int node,
                      const unsigned int) const override
    {
      return constraint_of(node)->outward;
    }

    /** A held contact node does not slip. */
    double
    friction_coefficient(const unsigned int,
                         const unsigned int) const override
    {
      return std::numeric_limits<double>::infinity();
    }

  private:
    /** setup(), also when a wall ends (the nodes are a cache of time). */
    void
    find_nodes() const;

    /** The projection of constrain_velocity(). */
    void
    apply(const unsigned int node, double *vector_at_node) const
    {
      const int c = constraint_of_node[node];
      if (c < 0)
        return;
      const Constraint &constraint = constraints[c];
      if (constraint.n_normals == dim)
        {
          for (unsigned int d = 0; d < dim; ++d)
            vector_at_node[d] = 0.;
          return;
        }
      for (unsigned int k = 0; k < constraint.n_normals; ++k)
        {
          double dot = 0.;
          for (unsigned int d = 0; d < dim; ++d)
            dot += vector_at_node[d] * constraint.normals[k][d];
          for (unsigned int d = 0; d < dim; ++d)
            vector_at_node[d] -= dot * constraint.normals[k][d];
        }
    }

  public:
    /** The directions a node may not move in. */
    struct Constraint
    {
      /** Orthonormal; n_normals == dim means fixed. */
      std::array<Tensor<1, dim>, dim> normals;
      unsigned int                    n_normals = 0;
      /**
       * A contact node: fixed only while the wall pushes the material.
       * `outward` is the wall's unit normal pointing out of the grid.
       */
      bool           unilateral = false;
      Tensor<1, dim> outward;
    };

    /** Whether any named boundary is a contact boundary. */
    bool
    has_contact() const
    {
      return !contact_ids.empty();
    }

    enum class WallKind
    {
      none,
      fixed,
      slip,
      contact
    };

    /** The condition on the boundary faces with this id. */
    WallKind
    kind_of(const types::boundary_id id) const
    {
      auto in = [id](const std::vector<types::boundary_id> &ids) {
        return std::find(ids.begin(), ids.end(), id) != ids.end();
      };
      return in(fixed_ids)   ? WallKind::fixed :
             in(slip_ids)    ? WallKind::slip :
             in(contact_ids) ? WallKind::contact :
                               WallKind::none;
    }

    /** The constraint of a node (a Grid node id), or nullptr. */
    const Constraint *
    constraint_of(const unsigned int node) const
    {
      const int c = constraint_of_node[node];
      return c < 0 ? nullptr : &constraints[c];
    }

  private:
    const Grid<dim> &grid;

    std::vector<types::boundary_id> fixed_ids;
    std::vector<types::boundary_id> slip_ids;
    std::vector<types::boundary_id> contact_ids;
    std::vector<std::string>        fixed_names;
    std::vector<std::string>        slip_names;
    std::vector<std::string>        contact_names;

    /** The walls given 'until', and when they end. */
    std::map<types::boundary_id, double> end_times;
    /** The time at which the walls in force were last found. */
    mutable double found_at = 0.;

    /** Per node id: index into `constraints`, or -1. */
    mutable std::vector<int>        constraint_of_node;
    mutable std::vector<Constraint> constraints;

    boost::signals2::scoped_connection grid_changed;
  };
} // namespace mpm

#endif
