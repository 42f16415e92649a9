#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/solvers/linear_solver.h>
#include <fdparticle/solvers/newton_solver.h>

#include <algorithm>
#include <cmath>

namespace fdparticle
{
  void NewtonSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    {
      prm.declare_entry("Nonlinear tolerance", "1e-10", Patterns::Double(0),
                        "Newton stops when the residual 2-norm is below this value, or below "
                        "this value times the residual at the start of the step.");
      prm.declare_entry("Max nonlinear iterations", "20", Patterns::Integer(1),
                        "Newton iterations allowed per time step.");
      prm.declare_entry("Line search", "true", Patterns::Bool(),
                        "Halve the Newton step until the residual decreases (Navier-Stokes).");
      prm.declare_entry("Reuse Jacobian", "true", Patterns::Bool(),
                        "Within a time step, keep the factored Jacobian while each iteration "
                        "still reduces the residual tenfold (saves factorizations at low "
                        "Reynolds number); false: exact Newton, a new Jacobian every iteration.");
      prm.declare_entry("Initial guess", "last step", Patterns::Selection("last step|extrapolated"),
                        "Where Newton starts a time step. last step: the last step's state. "
                        "extrapolated: of the last step's state and the fluid unknowns and free "
                        "particles' velocities extrapolated linearly from the last two steps, the "
                        "one with the smaller residual (two residual evaluations more a step; "
                        "a step of order 1 starts from the last step). It saves Newton "
                        "iterations in a flow that changes smoothly; where that saves time: "
                        "doc/performance.md. The converged step is the same to the nonlinear "
                        "tolerance.");
    }
    prm.leave_subsection();
  }

  void NewtonSolver::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    tolerance      = prm.get_double("Nonlinear tolerance");
    max_iterations = prm.get_integer("Max nonlinear iterations");
    line_search    = prm.get_bool("Line search");
    reuse_jacobian = prm.get_bool("Reuse Jacobian");
    extrapolate    = prm.get("Initial guess") == "extrapolated";
    prm.leave_subsection();
  }

  NewtonSolver::Result NewtonSolver::solve(const Problem &problem) const
  {
    using ParameterTools::format_short;
    Result result;
    auto   where = [&]() {
      return problem.describe_residual ? " (" + problem.describe_residual() + ")" : std::string();
    };
    auto fail = [&](const Outcome outcome, const std::string &message) {
      result.outcome = outcome;
      result.message = message;
      return result;
    };

    double residual         = problem.assemble(true);
    result.initial_residual = residual;
    // A non-finite start must not make the target infinite and the step "converged".
    const double target = tolerance * std::max(1.0, std::isfinite(residual) ? residual : 1.0);
    // Written so that a NaN residual enters the loop (NaN <= target is false) and is
    // caught there.
    double previous = residual, forcing = max_forcing;
    // A linear problem takes one exact correction with the full step. If the residual is
    // still above the target after it, a force that is not linear in the unknowns acts (a
    // contact or lubrication force, evaluated where the particles end the step): Newton
    // goes on as for a nonlinear problem.
    bool linear = problem.linear;
    while (!(residual <= target))
      {
        result.residual = residual;
        if (!std::isfinite(residual))
          return fail(Outcome::not_finite, "the residual is not finite" + where());
        if (residual > divergence_factor * std::max(result.initial_residual, target))
          return fail(Outcome::diverged, "Newton diverges: the residual grew from " +
                                           format_short(result.initial_residual) + " to " +
                                           format_short(residual) + where());
        if (result.iterations >= max_iterations)
          return fail(Outcome::too_many_iterations,
                      "Newton did not converge in " + std::to_string(max_iterations) +
                        " iterations (residual " + format_short(residual) + " from " +
                        format_short(result.initial_residual) +
                        (problem.describe_residual ? "; " + problem.describe_residual() : "") +
                        ")");
        // Inexact Newton (doc/method.md §5; Eisenstat & Walker 1996, choice 2): the
        // linear solve reduces its residual by the forcing term, which tightens as Newton
        // converges, and never further than the target needs.
        if (result.iterations > 0)
          {
            const double safeguard = forcing_gamma * forcing * forcing;
            forcing = forcing_gamma * (residual / previous) * (residual / previous);
            if (safeguard > forcing_safeguard_threshold)
              forcing = std::max(forcing, safeguard);
          }
        forcing = std::min(max_forcing, forcing);
        if (linear)
          forcing = 0;
        forcing = std::max(forcing, target_margin * target / residual);
        try
          {
            result.linear_iterations += problem.solve(forcing);
          }
        catch (const OutOfMemory &e)
          {
            return fail(Outcome::out_of_memory, ParameterTools::one_line_message(e));
          }
        catch (const std::exception &e)
          {
            return fail(Outcome::linear_solver_failed,
                        "the linear solve failed: " + ParameterTools::one_line_message(e));
          }
        ++result.iterations;
        if (linear)
          {
            problem.apply_update(1.0);
            previous = residual;
            residual = problem.assemble(false);
            if (residual <= target)
              break;
            linear   = false;
            residual = problem.assemble(true);
            continue;
          }
        double theta = 1.0, trial;
        for (;;)
          {
            problem.apply_update(theta);
            trial = problem.assemble(false);
            if (!line_search || trial < residual || theta < line_search_floor)
              break;
            theta *= 0.5;
          }
        previous = residual;
        residual = trial;
        if (residual > target && (!reuse_jacobian || residual > jacobian_reuse_reduction * previous))
          residual = problem.assemble(true);
      }
    result.residual = residual;
    return result;
  }
} // namespace fdparticle
