#ifndef mpm_time_implicit_integrator_h
#define mpm_time_implicit_integrator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/hp/fe_collection.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/particles/particle_handler.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <boost/serialization/set.hpp>

#include <mpm/basis/grid_basis.h>
#include <mpm/grid/grid.h>
#include <mpm/basis/meshfree_basis.h>
#include <mpm/basis/node_cloud.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>

#include <memory>
#include <set>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Implicit MPM: each step solves for the nodal displacement increment by
   * Newton-Raphson, with the internal force and tangent of PointAssembly on
   * Trilinos. Only cells that hold points carry unknowns (FE_Nothing
   * elsewhere), so the matrix stays regular and its size follows the
   * material. After convergence the points take the step's deformation and
   * displacement, and the grid is reset.
   *
   * - Quasi-static (Beuth et al. section 3): equilibrium with gravity and
   *   point loads scaled by a load factor.
   * - Newmark (Iaconeta et al. 2017, Algorithm 1): nodal velocity and
   *   acceleration projected from the points, inertia m_p a(x_p) at the
   *   points with the Newmark update of the nodal acceleration, the
   *   consistent point mass m_p N_i N_k / (beta dt^2) in the tangent, and the
   *   points' velocity and acceleration updated from the nodes ([I] eqs.
   *   46-49).
   *
   * With a MeshfreeBasis the same steps run on the Galerkin meshfree
   * method ([I] Algorithm 2): the unknowns are those of a NodeCloud, whose
   * nodes move with the solution and keep their velocity and acceleration
   * as history, and each point's support comes from MLS or LME shape
   * functions. Assembly, Newton, Newmark, materials and output are the
   * same code: both methods reach them only through PointGroup.
   */
  template <int dim>
  class ImplicitIntegrator
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    ImplicitIntegrator(const bool                                    dynamic,
                       ParameterHandler &                            prm,
                       MaterialPoints<dim> &                         points,
                       const Grid<dim> &                             grid,
                       const GridBasis<dim> &                        basis,
                       const DirichletConditions<dim> &              dirichlet,
                       const std::vector<std::unique_ptr<Material>> &materials,
                       const Tensor<1, dim> &                        gravity,
                       ConditionalOStream &                          pcout,
                       TimerOutput &                                 timer,
                       std::unique_ptr<MeshfreeBasis<dim>> meshfree = {});

    /** The meshfree nodes, or nullptr for MPM. */
    const NodeCloud<dim> *
    node_cloud() const
    {
      return cloud.get();
    }

    /** The meshfree basis, or nullptr for MPM. */
    const MeshfreeBasis<dim> *
    meshfree_basis() const
    {
      return meshfree.get();
    }

    /**
     * Solve one step and move the points. `load_factor` scales gravity and
     * point loads (1 in dynamic runs); dt is the time step (dynamic runs
     * only). A step that does not converge throws RunError and leaves the
     * points as they were.
     */
    void
    step(const double load_factor, const double dt);

    /**
     * The state carried from step to step, for Checkpoint: the walls'
     * active set and the meshfree nodes. Everything else is built again
     * at every step. The contact nodes are numbered on this rank, so a
     * checkpoint is continued on as many ranks.
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &engaged_contact_nodes;
      if (cloud)
        archive &*cloud;
      if (meshfree)
        archive &*meshfree;
    }

  private:
    /**
     * Points that share one list of unknowns, node-major: the points of a
     * cell (MPM) or a single point (GMM), each with its support at the
     * start of the step, whose node i carries dofs[i * dim + a].
     */
    struct PointGroup
    {
      std::vector<types::global_dof_index> dofs;
      /** Factor on the point volumes (see quadrature_scale()). */
      double weight = 1.;
      std::vector<typename Particles::ParticleHandler<dim>::particle_iterator>
                                particles;
      std::vector<Support<dim>> supports;
    };

    void
    setup_system();

    /** step() without restoring the active set when it throws. */
    void
    solve_step(const double load_factor, const double dt);

    /** The GMM counterpart of setup_system(): supports, unknowns, pattern. */
    void
    setup_cloud_system();

    /** GMM: the pattern of the points' supports under the constraints. */
    DynamicSparsityPattern
    cloud_sparsity_pattern() const;

    /**
     * Trilinos objects for the current owned and relevant dofs and the
     * pattern `dsp`.
     */
    void
    reinit_linear_system(DynamicSparsityPattern &dsp);

    /** The next group to fill, counting in n_groups. */
    PointGroup &
    next_group(unsigned int &n_groups);

    /** One group per cell that holds points (MPM). */
    void
    build_cell_groups();

    /**
     * GMM conditions on the nodes that start on walls. LME interpolates on
     * the boundary of the cloud's hull (weak Kronecker delta), so the held
     * components of those nodes are set to zero. MLS does not: there the
     * interpolated displacement at each held node, sum_j N_j(x_d) u_j, is
     * set to zero, which ties the held nodes' values to their free
     * neighbours.
     */
    void
    make_cloud_constraints();

    /**
     * The displacement increment, and in dynamic runs the nodal velocity
     * and acceleration at the start, of each node of a group.
     */
    void
    gather(const PointGroup &           group,
           std::vector<Tensor<1, dim>> &du,
           std::vector<Tensor<1, dim>> &v_n,
           std::vector<Tensor<1, dim>> &a_n) const;

    /** GMM: the nodes take the step's displacement and Newmark update. */
    void
    move_cloud();

    /**
     * Grid conditions on the nodes of active cells as constraints; contact
     * nodes only while engaged.
     */
    void
    make_constraints();

    /**
     * Call f(cell, vertex, node, constraint) for each vertex with a grid
     * condition of each locally owned cell that holds points.
     */
    template <typename Function>
    void
    for_each_constrained_vertex(const Function &f) const;

    /** Call f(node, first dof, constraint) once per contact node. */
    template <typename Function>
    void
    for_each_contact_node(const Function &f) const;

    /**
     * Per contact node (at its first dof, ghosted): nonzero where material
     * touches the wall, that is a point in an adjacent cell lies closer to
     * the wall than half its spacing. After a solve, at the points' new
     * positions and only for points that moved towards the wall.
     */
    TrilinosWrappers::MPI::Vector
    contact_gaps(const bool after_solve) const;

    /**
     * After a converged solve: release engaged contact nodes whose wall
     * force pulls the material, and engage free ones where material closes
     * on the wall. Returns whether the contact set changed (on any rank).
     */
    bool
    update_contact_set();

    /** The step's nodal v and a at the start under the current constraints. */
    void
    constrain_initial_conditions();

    /** Nodal velocity and acceleration from the points (dynamic runs). */
    void
    project_initial_conditions();

    /**
     * Newmark: the nodal acceleration at the end of the step from the
     * displacement increment du and the nodal v and a at the start.
     */
    Tensor<1, dim>
    end_acceleration(const Tensor<1, dim> &du,
                     const Tensor<1, dim> &v,
                     const Tensor<1, dim> &a) const
    {
      return (du - time_step * v -
              time_step * time_step * (0.5 - beta) * a) /
             (beta * time_step * time_step);
    }

    /** Newmark: the velocity gained over the step from a at its ends. */
    Tensor<1, dim>
    velocity_increment(const Tensor<1, dim> &a_old,
                       const Tensor<1, dim> &a_new) const
    {
      return time_step * ((1. - gamma) * a_old + gamma * a_new);
    }

    /**
     * How far the material of a point reaches beyond it, half its spacing:
     * the distance at which a wall holds it.
     */
    static double
    reach_of(const ArrayView<const double> &p)
    {
      using Layout = PointLayout<dim>;
      return 0.5 *
             std::pow(determinant(Layout::get_deformation_gradient(p)) *
                        p[Layout::reference_volume],
                      1. / dim);
    }

    /** Residual f_ext - f_int into `residual`, and the tangent if asked. */
    void
    assemble(const double load_factor, const bool with_tangent);

    /**
     * Add a group's matrix into `tangent` when all its dofs are owned here
     * and unconstrained, and return true; otherwise leave it to
     * AffineConstraints and return false. Epetra's SumIntoGlobalValues
     * maps and searches every entry: with the meshfree supports (48 x 48
     * entries a point for LME 1.8) that was most of an assembly. Here each
     * column is mapped once, and each row is searched in one sweep.
     */
    bool
    add_to_tangent(const std::vector<types::global_dof_index> &dofs,
                   const FullMatrix<double> &                  matrix);

    /**
     * Factor on the point volumes of a cell in the quadrature of the
     * internal force (see the Integration parameter).
     */
    double
    quadrature_scale(
      const typename DoFHandler<dim>::active_cell_iterator &cell) const;

    /**
     * Newton/Check tangent: print how far the assembled tangent is from
     * central differences of the residual along one direction. Leaves the
     * residual and the displacement as they were.
     */
    void
    report_tangent_error(const double load_factor);

    void
    solve_linear_system();

    /**
     * Newton-Raphson from the current displacement under the current
     * constraints; throws RunError if it does not converge.
     */
    void
    solve_newton(const double load_factor);

    /**
     * After displacement += correction: halve the correction (up to 5
     * times) until the out-of-balance force falls below `residual_norm`,
     * its norm before the correction; keeps 1/32 of it if none does.
     * Each trial is a full assembly (with the tangent unless modified
     * Newton), so the system at the iterate kept is assembled already:
     * returns whether it is (false if the last trial failed or its
     * residual is not finite).
     */
    bool
    search_along_correction(const double load_factor,
                            const double residual_norm);

    /**
     * What the law sees of a step with deformation increment dF from F_n:
     * F_new = dF F_n, and the velocity gradient L = (dF - I) / dt over the
     * step (or load step, in pseudo-time), so rate laws see their rate.
     */
    StepKinematics
    step_kinematics(const Tensor<2, dim> &dF, const Tensor<2, dim> &F_n) const
    {
      StepKinematics k;
      k.F_old = PointLayout<dim>::embed(F_n, 1.);
      k.F_new = PointLayout<dim>::embed(dF * F_n, 1.);
      k.dt    = time_step;
      k.velocity_gradient = (PointLayout<dim>::embed(dF, 1.) -
                             Tensor<2, 3>(unit_symmetric_tensor<3>())) /
                            time_step;
      return k;
    }

    /** Deformation, stress and position of the converged step. */
    void
    update_points();

    MaterialPoints<dim> &                         points;
    const Grid<dim> &                             grid;
    const GridBasis<dim> &                        basis;
    const DirichletConditions<dim> &              dirichlet;
    const std::vector<std::unique_ptr<Material>> &materials;
    const Tensor<1, dim>                          gravity;
    ConditionalOStream &                          pcout;
    TimerOutput &                                 timer;

    double       tolerance;
    unsigned int max_iterations;
    bool         modified_newton;
    bool         linear_only;
    bool         line_search;
    bool         check_tangent;
    std::string  linear_solver;
    bool         scale_full_cells;
    bool         dynamic;
    double       bossak_alpha;
    double       beta;
    double       gamma;
    bool         lumped_mass;
    double       time_step = 0.;

    std::unique_ptr<MeshfreeBasis<dim>> meshfree;
    std::unique_ptr<NodeCloud<dim>>     cloud;
    std::vector<PointGroup>             groups;
    /** GMM: nodes in no point's support, held at zero. */
    std::vector<unsigned int>           unreached_nodes;

    hp::FECollection<dim>              fe_collection;
    DoFHandler<dim>                    dof_handler;
    IndexSet                           owned_dofs;
    IndexSet                           relevant_dofs;
    AffineConstraints<double>          constraints;
    TrilinosWrappers::SparseMatrix     tangent;
    /**
     * Scratch of add_to_tangent: a group's local columns, sorted, and
     * where each of them sits in the current row.
     */
    std::vector<std::pair<int, unsigned int>> tangent_columns;
    std::vector<int>                          tangent_offsets;
    /**
     * The direct solver's factorisation of `tangent`, made at the first
     * solve after the tangent was assembled or rebuilt: modified Newton
     * solves with one tangent many times. A direct solve needs no
     * tolerance, so its control logs nothing.
     */
    SolverControl direct_solver_control{1, 1e-10, false, false};
    std::unique_ptr<TrilinosWrappers::SolverDirect> factorization;
    TrilinosWrappers::MPI::Vector      residual;
    TrilinosWrappers::MPI::Vector      correction;
    TrilinosWrappers::MPI::Vector      displacement;
    TrilinosWrappers::MPI::Vector      displacement_ghosted;
    /**
     * Dynamic runs: nodal velocity and acceleration at the step's start, as
     * projected from the points and then under the grid conditions.
     */
    TrilinosWrappers::MPI::Vector      projected_velocity;
    TrilinosWrappers::MPI::Vector      projected_acceleration;
    TrilinosWrappers::MPI::Vector      velocity_ghosted;
    TrilinosWrappers::MPI::Vector      acceleration_ghosted;
    double                             external_force_norm = 0.;

    /**
     * Contact boundaries: f_ext - f_int - inertia before constraints (whose
     * negative is the wall force at a held node), and the contact nodes
     * (Grid node ids, stable while the grid does not change) that hold the
     * material.
     * A step starts from the previous step's set.
     */
    TrilinosWrappers::MPI::Vector      unconstrained_residual;
    std::set<unsigned int>             engaged_contact_nodes;
    /** Contact nodes that changed state in this step. */
    std::set<unsigned int>             changed_contact_nodes;
  };
} // namespace mpm

#endif
