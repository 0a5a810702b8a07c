#ifndef mpm_time_implicit_integrator_h
#define mpm_time_implicit_integrator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <mpm/basis/grid_basis.h>
#include <mpm/basis/meshfree_basis.h>
#include <mpm/basis/node_cloud.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/grid/grid.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>
#include <mpm/time/implicit_assembler.h>
#include <mpm/time/implicit_state.h>
#include <mpm/time/implicit_system.h>
#include <mpm/time/newmark.h>
#include <mpm/time/newton_solver.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * One implicit step: each step solves for the nodal displacement
   * increment by Newton-Raphson, then the points take the step's
   * deformation and displacement, and the grid is reset.
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
   * The parts, in the order a step calls them: the ImplicitSystem numbers
   * the step's unknowns and groups the points (GridSystem for MPM,
   * CloudSystem for the Galerkin meshfree method, [I] Algorithm 2); the
   * NewtonSolver iterates with the ImplicitAssembler's residual and
   * tangent; the system's active set of walls is corrected until it holds;
   * then update_points() moves the points. Both methods reach the assembly,
   * Newton, Newmark, the materials and the output only through the
   * ImplicitState.
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
                       const std::vector<const NodalCondition<dim> *> &conditions,
                       const DirichletConditions<dim> &              dirichlet,
                       const std::vector<std::unique_ptr<Material>> &materials,
                       const Tensor<1, dim> &                        gravity,
                       ConditionalOStream &                          pcout,
                       TimerOutput &                                 timer,
                       std::unique_ptr<MeshfreeBasis<dim>> meshfree = {});

    /**
     * Solve one step and move the points. `load_factor` scales gravity and
     * point loads (1 in dynamic runs); dt is the time step (dynamic runs
     * only). A step that does not converge throws RunError and leaves the
     * points, and the walls' active set, as they were.
     */
    void
    step(const double load_factor, const double dt);

    /** The meshfree nodes, or nullptr for MPM. */
    const NodeCloud<dim> *
    node_cloud() const
    {
      return system->node_cloud();
    }

    /** The meshfree basis, or nullptr for MPM. */
    const MeshfreeBasis<dim> *
    meshfree_basis() const
    {
      return system->meshfree_basis();
    }

    /**
     * The state carried from step to step, for Checkpoint: the system's
     * (the walls' active set, the meshfree nodes). Everything else is
     * built again at every step.
     */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      if constexpr (Archive::is_saving::value)
        system->save(archive);
      else
        system->load(archive);
    }

  private:
    /** step() without restoring the active set when it throws. */
    void
    solve_step(const double load_factor, const double dt);

    /** Deformation, stress and position of the converged step. */
    void
    update_points();

    MaterialPoints<dim> &                         points;
    const std::vector<std::unique_ptr<Material>> &materials;
    TimerOutput &                                 timer;

    ImplicitState<dim>                   state;
    Newmark                              newmark;
    std::unique_ptr<ImplicitSystem<dim>> system;
    NewtonSolver<dim>                    newton;
    ImplicitAssembler<dim>               assembler;
  };
} // namespace mpm

#endif
