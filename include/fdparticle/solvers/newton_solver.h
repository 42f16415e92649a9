#ifndef fdparticle_solvers_newton_solver_h
#define fdparticle_solvers_newton_solver_h

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <string>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Newton's method for one time step (doc/method.md §5), independent of what the unknowns
   * are: the caller supplies the problem as callbacks, this class decides when to
   * assemble a new Jacobian, how far to step (backtracking line search) and when to give
   * up. A linear problem (Stokes) is the special case of one correction with the full step,
   * unless a force that is not linear (contacts in a Stokes step) leaves the residual above
   * the target: then Newton goes on as for a nonlinear problem.
   *
   * Modified Newton: the Jacobian (and the linear solver's operator built from it) is kept
   * while each iteration still cuts the residual by jacobian_reuse_reduction; "Reuse
   * Jacobian = false" gives exact Newton.
   */
  class NewtonSolver
  {
  public:
    /// Why a solve ended. Every reason but converged lets the time loop retry with a
    /// smaller step (doc/method.md §5, recovery of failed steps).
    enum class Outcome
    {
      converged,
      not_finite,           ///< the residual became NaN or infinite
      diverged,             ///< the residual grew by more than divergence_factor
      too_many_iterations,  ///< Max nonlinear iterations reached
      linear_solver_failed, ///< the linear solve threw (e.g. a singular particle block)
      out_of_memory         ///< the linear solve could not allocate its memory
    };

    struct Result
    {
      Outcome      outcome = Outcome::converged;
      /// Newton corrections computed.
      unsigned int iterations       = 0;
      /// Iterations of the linear solves, summed (one per solve for a direct solver).
      unsigned int linear_iterations = 0;
      double       initial_residual = 0;
      double       residual         = 0;
      /// Why it failed, in words (empty when converged).
      std::string  message;

      bool converged() const { return outcome == Outcome::converged; }
    };

    /// The problem, as the solver sees it.
    struct Problem
    {
      /// Assemble the residual at the current state (and the Jacobian if with_jacobian);
      /// return the residual's 2-norm.
      std::function<double(bool with_jacobian)> assemble;
      /// Compute the correction from the last assembled Jacobian and residual, reducing
      /// the linear residual by the given factor (an iterative solver; a direct one is
      /// exact); return the linear iterations. Throws a std::exception if the linear
      /// solve fails.
      std::function<unsigned int(double relative_tolerance)> solve;
      /// Set the state to the state before the last solve() plus theta times its correction.
      std::function<void(double theta)> apply_update;
      /// Where the residual is largest, for the failure messages (may be empty).
      std::function<std::string()> describe_residual;
      /// A linear problem: one exact correction with the full step, no line search; if the
      /// residual is still above the target after it, Newton goes on as for a nonlinear one.
      bool linear = false;
    };

    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    /// Solve from the caller's current state. Never throws for a failed solve: the result
    /// says what happened.
    Result solve(const Problem &problem) const;

    double       tolerance      = 1e-10;
    unsigned int max_iterations = 20;
    bool         line_search    = true;
    bool         reuse_jacobian = true;
    /// Try the state extrapolated from the last two steps as a start (`Initial guess`);
    /// read by the caller, which owns the state and compares the two residuals.
    bool         extrapolate    = false;

    /// A residual this many times the larger of the initial residual and the target is
    /// divergence: far above the transient growth of a converging solve, far below
    /// overflow, so a diverging step is retried with a smaller Δt while its numbers still
    /// say something.
    static constexpr double divergence_factor = 1e6;
    /// The line search halves the step while the residual does not decrease, and takes the
    /// step once it is below this fraction of the correction (after five halvings, 1/32):
    /// the search must end, since the direction of a reused Jacobian need not be a descent
    /// direction, and each halving costs a residual assembly.
    static constexpr double line_search_floor = 1.0 / 16;
    /// Modified Newton keeps the Jacobian while an iteration cuts the residual at least
    /// tenfold: a reused Jacobian that contracts slower than that costs more iterations
    /// (each an assembly and a solve) than a new factorization saves.
    static constexpr double jacobian_reuse_reduction = 0.1;
    /// Inexact Newton: the loosest linear tolerance. Looser solves than a tenfold
    /// reduction give corrections the line search has to cut back.
    static constexpr double max_forcing = 0.1;
    /// Eisenstat & Walker's choice 2 (γ = 0.9, exponent 2) and its safeguard against a
    /// tolerance that drops faster than the residual (applied above 0.1), as they
    /// recommend.
    static constexpr double forcing_gamma               = 0.9;
    static constexpr double forcing_safeguard_threshold = 0.1;
    /// The linear solve of the last iteration reaches half the Newton target, so that the
    /// update, not round-off in the solve, decides convergence.
    static constexpr double target_margin = 0.5;
  };
} // namespace fdparticle

#endif
