#ifndef fdparticle_solvers_iterative_solver_h
#define fdparticle_solvers_iterative_solver_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/block_preconditioner.h>
#include <fdparticle/solvers/bordered_operator.h>
#include <fdparticle/solvers/linear_solver.h>
#include <fdparticle/solvers/newton_system.h>

#include <Eigen/Dense>

#include <memory>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The Newton system solved by GMRES and FGMRES on the whole bordered matrix [A B; C D],
   * with the BlockPreconditioner (doc/method.md §8, iterative solve). Memory and work per
   * iteration are linear in the number of unknowns; the particle unknowns are a small
   * block of the Krylov vectors, not eliminated.
   *
   * The preconditioner is built with the first solve after operator_changed(), and kept
   * for later operators while it still converges about as fast as on the operator it was
   * built for: its reference is the largest number of outer iterations per decade of
   * residual reduction among the solves with that operator; a solve with a later operator
   * that needs more than rebuild_growth times as many marks it as drifted, and it is
   * rebuilt at the next operator_changed(). It is never rebuilt for the operator it was
   * built for (Newton with a reused Jacobian), which it cannot approximate better.
   *
   * Each solve first tries cheap_iterations GMRES iterations, preconditioned from the
   * right, with the cheap form of the preconditioner (no inner solve,
   * BlockPreconditioner::inner_solve off; a fixed linear operator, so GMRES needs one
   * vector per iteration where FGMRES keeps two) and, if they do not reach the tolerance,
   * continues from there by FGMRES with the inner solve (as ASPECT's Stokes solver does).
   * When the cheap form fails with a preconditioner built for an earlier operator, the
   * preconditioner is rebuilt for this one and the cheap form tried
   * once more from where it stopped; the rate of the solve counts from there. A
   * preconditioner whose cheap form failed on its own operator is used with the inner
   * solve until it is rebuilt.
   */
  class IterativeSolver : public LinearSolver
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    std::string   name() const override { return "iterative"; }
    bool          iterative() const override { return true; }
    /// The Schur complement approximation reads the cells' pressure mass matrices; with
    /// the multigrid the velocity block is the program's, applied without a matrix.
    AssembledData assembled_data() const override { return {true, velocity_multigrid}; }
    void      pattern_changed() override;
    void      operator_changed() override;
    SolveInfo solve(const NewtonSystem &system, const double tolerance,
                    TrilinosWrappers::MPI::Vector &x, Eigen::VectorXd &y) override;

  private:
    unsigned int max_iterations   = 500;
    unsigned int cheap_iterations = 100;
    unsigned int basis_size     = 50;
    bool         reuse          = true;
    bool         verbose        = false;
    bool         velocity_multigrid = true;
    /// See the class documentation: a preconditioner that needs more than this many times
    /// its reference iterations per decade has drifted too far from the operator. 1.5: the
    /// reference is already the slowest solve with the fresh preconditioner (the rate
    /// varies severalfold on one Jacobian with the right-hand side and the tolerance), so a
    /// drift must make a solve half again as slow as the worst of those; a rebuild costs
    /// tens of iterations' time (doc/performance.md).
    static constexpr double rebuild_growth = 1.5;
    /// Solves that reduce their residual less than tenfold are too short to give a rate.
    static constexpr double min_rate_decades = 1;

    std::unique_ptr<BorderedOperator> op;
    BlockPreconditioner               preconditioner;
    bool                              stale = true;
    /// No operator_changed() since the preconditioner was built.
    bool                              fresh = false;
    /// A solve with a later operator converged too slowly: rebuild with the next operator.
    bool                              drifted = false;
    /// Outer iterations per decade of residual reduction: the largest among the solves
    /// with the operator the preconditioner was built for (0: none measured yet).
    double                            reference_rate = 0;
    /// Whether the cheap form of the current preconditioner failed to converge.
    bool                              cheap_failed = false;
    /// Non-zeros of the velocity block for the statistics line, counted once per sparsity
    /// pattern (invalid: not yet).
    types::global_dof_index velocity_nonzeros = numbers::invalid_dof_index;
  };
} // namespace fdparticle

#endif
