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
   * The Newton system solved by FGMRES on the whole bordered matrix [A B; C D], with the
   * BlockPreconditioner (doc/method.md §8, iterative solve). Memory and work per
   * iteration are linear in the number of unknowns; the particle unknowns are a small
   * block of the Krylov vectors, not eliminated.
   *
   * The preconditioner is built with the first solve after operator_changed(), and kept
   * for later operators while it still converges quickly: a solve that needed more than
   * rebuild_growth times the iterations of the first solve with the current
   * preconditioner marks it for a rebuild at the next operator_changed().
   *
   * Each solve first tries cheap_iterations FGMRES iterations with the cheap form of the
   * preconditioner (no inner solve, BlockPreconditioner::inner_solve off) and, if they do
   * not reach the tolerance, continues from there with the inner solve (as ASPECT's
   * Stokes solver does). A preconditioner whose cheap form failed once is used with the
   * inner solve until it is rebuilt.
   */
  class IterativeSolver : public LinearSolver
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    bool      iterative() const override { return true; }
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
    /// See the class documentation: a preconditioner that needs more than this many times
    /// its first iteration count has drifted too far from the operator.
    static constexpr double rebuild_growth = 1.5;

    std::unique_ptr<BorderedOperator> op;
    BlockPreconditioner               preconditioner;
    bool                              stale = true;
    /// Iterations of the first solve with the current preconditioner.
    unsigned int                      reference_iterations = 0;
    /// Whether the cheap form of the current preconditioner failed to converge.
    bool                              cheap_failed = false;
  };
} // namespace fdparticle

#endif
