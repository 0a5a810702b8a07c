#ifndef mpm_time_implicit_state_h
#define mpm_time_implicit_state_h

#include <deal.II/base/index_set.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/particles/particle_handler.h>

#include <mpm/basis/support.h>

#include <map>
#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * What the parts of an implicit step share: the unknowns of the step
   * (built by an ImplicitSystem), the points grouped by the unknowns they
   * touch, the constraints, the tangent and the vectors of Newton's
   * iteration. The system fills it, the assembler and the Newton solver
   * work on it, and the integrator moves the points from it.
   */
  template <int dim>
  struct ImplicitState
  {
    /**
     * Points that share one list of unknowns, node-major: the points of a
     * cell (MPM) or a single point (GMM), each with its support at the
     * start of the step, whose node i carries dofs[i * dim + a].
     */
    struct PointGroup
    {
      std::vector<types::global_dof_index> dofs;
      /** Factor on the point volumes (the quadrature of full cells). */
      double weight = 1.;
      std::vector<typename Particles::ParticleHandler<dim>::particle_iterator>
                                particles;
      std::vector<Support<dim>> supports;
    };

    /** The next group to fill, counting in n_groups. */
    PointGroup &
    next_group(unsigned int &n_groups)
    {
      // Groups are reused from step to step, so that their vectors keep
      // their memory.
      if (n_groups == groups.size())
        groups.emplace_back();
      PointGroup &group = groups[n_groups++];
      group.particles.clear();
      group.weight = 1.;
      return group;
    }

    /**
     * Trilinos objects for the current owned and relevant dofs and the
     * pattern `dsp`.
     */
    void
    reinit(DynamicSparsityPattern &dsp, const MPI_Comm communicator)
    {
      factorization.reset();
      tangent.reinit(owned_dofs, owned_dofs, dsp, communicator);
      residual.reinit(owned_dofs, communicator);
      correction.reinit(owned_dofs, communicator);
      displacement.reinit(owned_dofs, communicator);
      displacement_ghosted.reinit(owned_dofs, relevant_dofs, communicator);
      velocity_ghosted.reinit(owned_dofs, relevant_dofs, communicator);
      acceleration_ghosted.reinit(owned_dofs, relevant_dofs, communicator);
      if (keeps_unconstrained_residual)
        unconstrained_residual.reinit(owned_dofs,
                                      relevant_dofs,
                                      communicator,
                                      true);
    }

    /**
     * The displacement increment, and in dynamic runs the nodal velocity
     * and acceleration at the start, of each node of a group.
     */
    void
    gather(const PointGroup &           group,
           std::vector<Tensor<1, dim>> &du,
           std::vector<Tensor<1, dim>> &v_n,
           std::vector<Tensor<1, dim>> &a_n) const
    {
      const unsigned int n = group.dofs.size();
      du.resize(n / dim);
      v_n.resize(n / dim);
      a_n.resize(n / dim);
      for (unsigned int i = 0; i < n; ++i)
        {
          du[i / dim][i % dim] = displacement_ghosted(group.dofs[i]);
          if (dynamic)
            {
              v_n[i / dim][i % dim] = velocity_ghosted(group.dofs[i]);
              a_n[i / dim][i % dim] = acceleration_ghosted(group.dofs[i]);
            }
        }
    }

    /** The step's nodal v and a at the start under the current constraints. */
    void
    constrain_initial_conditions()
    {
      TrilinosWrappers::MPI::Vector velocity(projected_velocity),
        acceleration(projected_acceleration);
      // Grid conditions hold for the nodal velocity and acceleration too.
      constraints.distribute(velocity);
      constraints.distribute(acceleration);
      velocity_ghosted     = velocity;
      acceleration_ghosted = acceleration;
    }

    /**
     * The out-of-balance force before constraints at every relevant dof,
     * zero unless it is kept: minus the wall force at a held node.
     */
    TrilinosWrappers::MPI::Vector
    wall_reactions(const MPI_Comm communicator) const
    {
      TrilinosWrappers::MPI::Vector ghosted(owned_dofs,
                                            relevant_dofs,
                                            communicator);
      if (keeps_unconstrained_residual)
        ghosted = unconstrained_residual;
      return ghosted;
    }

    /** Newmark (else quasi-static). */
    bool   dynamic   = false;
    double time_step = 0.;
    /**
     * Walls with an active set need the out-of-balance force before
     * constraints (whose negative is the wall force at a held node).
     */
    bool keeps_unconstrained_residual = false;

    /**
     * A node that slides on a wall with friction (the system's active
     * set): the wall's outward normal, the unit direction of the slide
     * and the Coulomb coefficient.
     */
    struct SlidingNode
    {
      Tensor<1, dim> outward;
      Tensor<1, dim> direction;
      double         friction;
    };

    std::vector<PointGroup> groups;
    /**
     * The sliding nodes of the locally owned groups, by the node's first
     * dof (a node may slide on two walls); empty without friction walls.
     */
    std::multimap<types::global_dof_index, SlidingNode> sliding_nodes;
    /**
     * The first dof of each locally owned node in no point's support (GMM;
     * MPM with shape functions that reach the cells around): held at zero,
     * with a unit diagonal that keeps the tangent regular.
     */
    std::vector<types::global_dof_index> unreached_node_dofs;

    IndexSet                       owned_dofs;
    IndexSet                       relevant_dofs;
    AffineConstraints<double>      constraints;
    TrilinosWrappers::SparseMatrix tangent;
    /**
     * The direct solver's factorisation of `tangent`, made at the first
     * solve after the tangent was assembled or rebuilt (modified Newton
     * solves with one tangent many times); whoever changes the tangent
     * resets it.
     */
    std::unique_ptr<TrilinosWrappers::SolverDirect> factorization;
    TrilinosWrappers::MPI::Vector                   residual;
    /** The Newton correction; f_ext while assembling. */
    TrilinosWrappers::MPI::Vector correction;
    TrilinosWrappers::MPI::Vector displacement;
    TrilinosWrappers::MPI::Vector displacement_ghosted;
    /**
     * Dynamic runs: nodal velocity and acceleration at the step's start, as
     * projected from the points and then under the constraints.
     */
    TrilinosWrappers::MPI::Vector projected_velocity;
    TrilinosWrappers::MPI::Vector projected_acceleration;
    TrilinosWrappers::MPI::Vector velocity_ghosted;
    TrilinosWrappers::MPI::Vector acceleration_ghosted;
    /** f_ext - f_int - inertia before constraints (see above). */
    TrilinosWrappers::MPI::Vector unconstrained_residual;
    /** The force scale of the out-of-balance ratio. */
    double external_force_norm = 0.;
  };
} // namespace mpm

#endif
