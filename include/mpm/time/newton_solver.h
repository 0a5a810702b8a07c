#ifndef mpm_time_newton_solver_h
#define mpm_time_newton_solver_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/solver_control.h>

#include <mpm/grid/grid.h>
#include <mpm/time/implicit_assembler.h>
#include <mpm/time/implicit_state.h>

#include <string>

namespace mpm
{
  using namespace dealii;

  /**
   * Newton-Raphson on the displacement increment of an implicit step, with
   * its variants (full, modified, linear), the line search, the check of
   * the assembled tangent and the linear solvers (Trilinos: KLU, MUMPS or
   * CG with ML AMG). The `Newton` subsection.
   */
  template <int dim>
  class NewtonSolver
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Parse the `Newton` subsection (the handler is at top level).
     * The grid's smallest cell edge sizes the tangent check's probe.
     */
    NewtonSolver(ParameterHandler &  prm,
                 const Grid<dim> &   grid,
                 ConditionalOStream &pcout,
                 TimerOutput &       timer);

    /**
     * Newton-Raphson from state.displacement under the current
     * constraints; throws RunError if it does not converge.
     */
    void
    solve(ImplicitState<dim> &     state,
          ImplicitAssembler<dim> &assembler,
          const double             load_factor);

  private:
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
    search_along_correction(ImplicitState<dim> &     state,
                            ImplicitAssembler<dim> &assembler,
                            const double             load_factor,
                            const double             residual_norm);

    /**
     * Newton/Check tangent: print how far the assembled tangent is from
     * central differences of the residual along one direction. Leaves the
     * residual and the displacement as they were.
     */
    void
    report_tangent_error(ImplicitState<dim> &     state,
                         ImplicitAssembler<dim> &assembler,
                         const double             load_factor);

    /** correction = tangent^-1 residual, within the constraints. */
    void
    solve_linear_system(ImplicitState<dim> &state);

    double              tolerance;
    unsigned int        max_iterations;
    bool                modified_newton;
    bool                linear_only;
    bool                line_search;
    bool                check_tangent;
    std::string         linear_solver;
    const Grid<dim> &   grid;
    ConditionalOStream &pcout;
    TimerOutput &       timer;
    /** A direct solve needs no tolerance, so its control logs nothing. */
    SolverControl direct_solver_control{1, 1e-10, false, false};
  };
} // namespace mpm

#endif
