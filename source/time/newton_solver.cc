#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <mpm/base/input_error.h>
#include <mpm/time/newton_solver.h>

#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <sstream>

namespace mpm
{
  template <int dim>
  void
  NewtonSolver<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Newton");
    prm.declare_entry("Tolerance", "1e-8", Patterns::Double(0.),
                      "Convergence when the out-of-balance force ratio "
                      "alpha = |f_ext - f_int| / |f_ext| (Beuth et al. eq. "
                      "31) falls below this.");
    prm.declare_entry("Maximum iterations", "25", Patterns::Integer(1),
                      "Iterations before a load step counts as failed and "
                      "is cut in half.");
    prm.declare_entry("Variant", "full",
                      Patterns::Selection("full|modified|linear"),
                      "full: a new tangent every iteration (quadratic "
                      "convergence). modified: the tangent of the step's "
                      "first iteration throughout, as in Beuth et al., "
                      "factorised once by the direct solvers (linear "
                      "convergence, cheap iterations). "
                      "linear: one iteration per load step, accepted as it "
                      "is; with one load step this is the small-strain "
                      "linear solution.");
    prm.declare_entry("Line search", "false", Patterns::Bool(),
                      "Backtrack along each Newton correction, halving it "
                      "up to 5 times, until the out-of-balance force falls. "
                      "For plastic runs in which points switch between the "
                      "planes, edges and apex of Mohr-Coulomb and full "
                      "Newton cycles. Each halving costs one more "
                      "assembly; the trial kept is the next iterate and is "
                      "not assembled again.");
    prm.declare_entry("Check tangent", "false", Patterns::Bool(),
                      "At each assembly of the tangent K, compare K d with "
                      "central differences of the out-of-balance force r "
                      "along a fixed pseudo-random direction d of size "
                      "3e-9 times the smallest cell (within the "
                      "constraints), and print |K d + (r(u + d) - r(u - "
                      "d)) / 2| / |K d| over the unconstrained rows: about "
                      "5e-8 (round-off) for a consistent tangent. A point "
                      "within d of a kink of its yield surface gives an "
                      "isolated larger value. For checking a new material "
                      "law or condition; costs two assemblies of the force "
                      "per check.");
    prm.declare_entry("Linear solver", "direct",
                      Patterns::Selection("direct|MUMPS|CG-AMG"),
                      "direct: sparse LU (KLU through Trilinos Amesos), for "
                      "small problems. MUMPS: the multifrontal sparse LU of "
                      "MUMPS (Amesos), faster on the wider patterns of the "
                      "meshfree methods (6 times on the column collapse "
                      "with GMM-LME at h = 0.05, with OpenBLAS) and on large "
                      "MPM grids (1.9 times on the column at h = 0.025, "
                      "51 200 points); as fast on small MPM grids. "
                      "CG-AMG: conjugate gradients with "
                      "Trilinos ML algebraic multigrid, for large problems "
                      "with a symmetric tangent (not for non-associated "
                      "plasticity).");
    prm.leave_subsection();
  }



  template <int dim>
  NewtonSolver<dim>::NewtonSolver(ParameterHandler &  prm,
                                  const Grid<dim> &   grid,
                                  ConditionalOStream &pcout,
                                  TimerOutput &       timer)
    : grid(grid)
    , pcout(pcout)
    , timer(timer)
  {
    prm.enter_subsection("Newton");
    tolerance       = prm.get_double("Tolerance");
    max_iterations  = prm.get_integer("Maximum iterations");
    modified_newton = prm.get("Variant") == "modified";
    linear_only     = prm.get("Variant") == "linear";
    line_search     = prm.get_bool("Line search");
    check_tangent   = prm.get_bool("Check tangent");
    if (line_search && linear_only)
      throw InputError("Newton/Line search does not go with Variant = "
                       "linear, which accepts its one iteration as it is.");
    linear_solver = prm.get("Linear solver");
    prm.leave_subsection();
    if (!(tolerance > 0.))
      throw InputError("Newton/Tolerance must be positive.");
  }



  template <int dim>
  void
  NewtonSolver<dim>::solve(ImplicitState<dim> &     state,
                           ImplicitAssembler<dim> &assembler,
                           const double             load_factor)
  {
    bool converged = false;
    bool assembled = false; // the line search assembled at this iterate
    for (unsigned int iteration = 0; iteration <= max_iterations; ++iteration)
      {
        // Modified Newton keeps the first iteration's tangent.
        const bool new_tangent = iteration == 0 || !modified_newton;
        if (!assembled)
          {
            TimerOutput::Scope t(timer, "assemble");
            assembler.assemble(state, load_factor, new_tangent);
          }
        const double ratio =
          state.external_force_norm > 0. ?
            state.residual.l2_norm() / state.external_force_norm :
            0.;
        // Formatted apart, so that the screen's precision stays as it is.
        std::ostringstream ratio_text;
        ratio_text << std::scientific << std::setprecision(3) << ratio;
        pcout << "    Newton " << std::setw(2) << iteration
              << ": out-of-balance ratio " << ratio_text.str() << std::endl;
        if (!std::isfinite(ratio))
          throw RunError("The out-of-balance force is not finite.");
        if (check_tangent && new_tangent)
          {
            TimerOutput::Scope t(timer, "tangent check");
            report_tangent_error(state, assembler, load_factor);
          }
        if (ratio < tolerance || (linear_only && iteration == 1))
          {
            converged = true;
            break;
          }
        if (iteration == max_iterations)
          break;
        {
          TimerOutput::Scope t(timer, "linear solve");
          solve_linear_system(state);
        }
        state.displacement += state.correction;
        state.displacement_ghosted = state.displacement;
        if (line_search)
          assembled =
            search_along_correction(state,
                                    assembler,
                                    load_factor,
                                    ratio * state.external_force_norm);
      }
    if (!converged)
      {
        std::ostringstream message;
        if (state.dynamic)
          message << "The time step of size " << state.time_step;
        else
          message << "The load step to load factor " << load_factor;
        message << " did not converge in " << max_iterations
                << " Newton iterations.";
        throw RunError(message.str());
      }
  }



  template <int dim>
  bool
  NewtonSolver<dim>::search_along_correction(
    ImplicitState<dim> &     state,
    ImplicitAssembler<dim> &assembler,
    const double             load_factor,
    const double             residual_norm)
  {
    // assemble() keeps f_ext in `correction`: save the direction first.
    const TrilinosWrappers::MPI::Vector direction(state.correction);
    constexpr unsigned int              max_cuts = 5;
    double                              step     = 1.;
    for (unsigned int cut = 0;; ++cut)
      {
        double trial = std::numeric_limits<double>::infinity();
        try
          {
            // With the tangent: the trial kept is the next Newton iterate.
            TimerOutput::Scope t(timer, "assemble");
            assembler.assemble(state, load_factor, !modified_newton);
            // Norms, not ratios: without external loads the scale is the
            // internal force, which the trial changes.
            trial = state.residual.l2_norm();
          }
        catch (const RunError &)
          {
            // An inverted point: too far along the correction.
          }
        if (trial < residual_norm || cut == max_cuts)
          {
            if (cut > 0)
              pcout << "    line search: 1/" << (1u << cut)
                    << " of the correction"
                    << (trial < residual_norm ? "" : ", no decrease")
                    << std::endl;
            return std::isfinite(trial);
          }
        step /= 2.;
        state.displacement.add(-step, direction);
        state.displacement_ghosted = state.displacement;
      }
  }



  template <int dim>
  void
  NewtonSolver<dim>::report_tangent_error(
    ImplicitState<dim> &     state,
    ImplicitAssembler<dim> &assembler,
    const double             load_factor)
  {
    // splitmix64 of the global dof index, in [-1, 1): a fixed direction
    // for a given numbering of the dofs.
    auto pseudo_random = [](std::uint64_t z) {
      z += 0x9E3779B97F4A7C15ull;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      z ^= z >> 31;
      return 2. * static_cast<double>(z >> 11) * 0x1.0p-53 - 1.;
    };
    // What assemble() overwrites, put back as it was afterwards.
    const TrilinosWrappers::MPI::Vector start(state.displacement);
    const TrilinosWrappers::MPI::Vector start_residual(state.residual);
    const TrilinosWrappers::MPI::Vector external_force(state.correction);
    TrilinosWrappers::MPI::Vector       start_unconstrained_residual;
    if (state.keeps_unconstrained_residual)
      start_unconstrained_residual = state.unconstrained_residual;
    const double start_external_force_norm = state.external_force_norm;

    const double probe_size = 3e-9 * grid.minimum_cell_size();
    TrilinosWrappers::MPI::Vector direction(state.displacement);
    for (const types::global_dof_index i : state.owned_dofs)
      direction[i] = probe_size * pseudo_random(i);
    direction.compress(VectorOperation::insert);
    // distribute() of u + d keeps the constraints' inhomogeneities, which
    // u satisfies, so the step taken is d within the constraints.
    TrilinosWrappers::MPI::Vector perturbed(start);
    perturbed += direction;
    state.constraints.distribute(perturbed);
    direction = perturbed;
    direction -= start;
    TrilinosWrappers::MPI::Vector tangent_times_direction(direction);
    state.tangent.vmult(tangent_times_direction, direction);

    auto assemble_at = [&](const TrilinosWrappers::MPI::Vector &u) {
      state.displacement         = u;
      state.displacement_ghosted = u;
      assembler.assemble(state, load_factor, false);
    };
    TrilinosWrappers::MPI::Vector mismatch;
    bool                          inverted = false;
    try
      {
        assemble_at(perturbed);
        mismatch  = state.residual;
        perturbed = start;
        perturbed -= direction;
        assemble_at(perturbed);
        mismatch -= state.residual;
      }
    catch (const RunError &)
      {
        inverted = true;
      }
    state.displacement           = start;
    state.displacement_ghosted   = start;
    state.residual               = start_residual;
    state.correction             = external_force;
    if (state.keeps_unconstrained_residual)
      state.unconstrained_residual = start_unconstrained_residual;
    state.external_force_norm    = start_external_force_norm;
    if (inverted)
      {
        pcout << "    tangent check: not made, u + d or u - d inverts a "
                 "point"
              << std::endl;
        return;
      }

    // r = f_ext - f_int - inertia and K = -dr/du.
    mismatch *= 0.5;
    mismatch += tangent_times_direction;
    for (const types::global_dof_index i : state.owned_dofs)
      if (state.constraints.is_constrained(i))
        {
          mismatch[i]                = 0.;
          tangent_times_direction[i] = 0.;
        }
    mismatch.compress(VectorOperation::insert);
    tangent_times_direction.compress(VectorOperation::insert);

    std::ostringstream error_text;
    error_text << std::scientific << std::setprecision(3)
               << mismatch.l2_norm() / tangent_times_direction.l2_norm();
    pcout << "    tangent check: |K d + (r(u + d) - r(u - d)) / 2| / |K d| = "
          << error_text.str() << std::endl;
  }



  template <int dim>
  void
  NewtonSolver<dim>::solve_linear_system(ImplicitState<dim> &state)
  {
    state.correction = 0.;
    try
      {
        if (linear_solver != "CG-AMG")
          {
            if (!state.factorization)
              {
                state.factorization =
                  std::make_unique<TrilinosWrappers::SolverDirect>(
                    direct_solver_control,
                    TrilinosWrappers::SolverDirect::AdditionalData(
                      false,
                      linear_solver == "MUMPS" ? "Amesos_Mumps" :
                                                 "Amesos_Klu"));
                state.factorization->initialize(state.tangent);
              }
            state.factorization->solve(state.correction, state.residual);
          }
        else
          {
            SolverControl control(1000,
                                  1e-10 * state.residual.l2_norm(),
                                  false,
                                  false);
            TrilinosWrappers::PreconditionAMG                 amg;
            TrilinosWrappers::PreconditionAMG::AdditionalData data;
            data.elliptic              = true;
            data.higher_order_elements = false;
            amg.initialize(state.tangent, data);
            SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
            cg.solve(state.tangent, state.correction, state.residual, amg);
          }
      }
    catch (const std::exception &e)
      {
        // A singular tangent or a solver that does not converge: the
        // residual norms are global, so every rank gets here together.
        throw RunError(std::string("The linear solver failed: ") + e.what());
      }
    state.constraints.distribute(state.correction);
  }



  template class NewtonSolver<2>;
  template class NewtonSolver<3>;
} // namespace mpm
