#ifndef mpm_time_quasi_static_integrator_h
#define mpm_time_quasi_static_integrator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/hp/fe_collection.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <mpm/basis/grid_basis.h>
#include <mpm/boundary/dirichlet_conditions.h>
#include <mpm/materials/material.h>
#include <mpm/points/material_points.h>

#include <memory>
#include <vector>

namespace mpm
{
  using namespace dealii;

  /**
   * Quasi-static MPM (Beuth et al. section 3): the load is applied in steps
   * of a pseudo-time; each step solves equilibrium of the points' internal
   * forces with gravity and point loads, scaled by the load factor t / T,
   * by Newton-Raphson on the nodal displacement increment, with the tangent
   * of PointAssembly on Trilinos. Only cells that hold points carry unknowns
   * (FE_Nothing elsewhere), so the matrix stays regular and its size follows
   * the material. After convergence the points take the step's deformation
   * and displacement, and the grid is reset.
   */
  template <int dim>
  class QuasiStaticIntegrator
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    QuasiStaticIntegrator(ParameterHandler &                            prm,
                          MaterialPoints<dim> &                         points,
                          const GridBasis<dim> &                        basis,
                          const DirichletConditions<dim> &              dirichlet,
                          const std::vector<std::unique_ptr<Material>> &materials,
                          const Tensor<1, dim> &                        gravity,
                          ConditionalOStream &                          pcout,
                          TimerOutput &                                 timer);

    /**
     * Solve the load step that ends at load factor `load_factor` and move
     * the points. A step that does not converge throws RunError.
     */
    void
    step(const double load_factor);

  private:
    void
    setup_system();

    /** Residual f_ext - f_int into `residual`, and the tangent if asked. */
    void
    assemble(const double load_factor, const bool with_tangent);

    /**
     * Factor on the point volumes of a cell in the quadrature of the
     * internal force (see the Integration parameter).
     */
    double
    quadrature_scale(
      const typename DoFHandler<dim>::active_cell_iterator &cell) const;

    void
    solve_linear_system();

    /** Deformation, stress and position of the converged step. */
    void
    update_points();

    MaterialPoints<dim> &                         points;
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
    std::string  linear_solver;
    bool         scale_full_cells;

    hp::FECollection<dim>              fe_collection;
    DoFHandler<dim>                    dof_handler;
    IndexSet                           owned_dofs;
    IndexSet                           relevant_dofs;
    AffineConstraints<double>          constraints;
    TrilinosWrappers::SparseMatrix     tangent;
    TrilinosWrappers::MPI::Vector      residual;
    TrilinosWrappers::MPI::Vector      correction;
    TrilinosWrappers::MPI::Vector      displacement;
    TrilinosWrappers::MPI::Vector      displacement_ghosted;
    double                             external_force_norm = 0.;
  };
} // namespace mpm

#endif
