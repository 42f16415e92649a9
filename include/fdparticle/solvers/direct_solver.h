#ifndef fdparticle_solvers_direct_solver_h
#define fdparticle_solvers_direct_solver_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/linear_solver.h>
#include <fdparticle/solvers/newton_system.h>

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

class Amesos_BaseSolver;
class Epetra_LinearProblem;
class Epetra_MultiVector;

namespace fdparticle
{
  using namespace dealii;

  /**
   * The Newton system solved by a sparse direct factorization of A (Amesos: MUMPS in
   * parallel, or KLU) and elimination of the particle unknowns y through the m×m Schur
   * complement S = D − C A⁻¹ B (doc/method.md §5). The first solve with an operator costs
   * one solve with m + 1 right-hand sides; A⁻¹B and S stay with the operator, so later
   * solves with it (modified Newton) need one right-hand side.
   *
   * The factorization has two stages: the symbolic one (ordering, analysis) depends only on
   * A's sparsity pattern and is kept until pattern_changed(); the numeric one depends on
   * A's values and is kept until operator_changed(). Both are done by solve() when needed.
   */
  class DirectSolver : public LinearSolver
  {
  public:
    DirectSolver();
    ~DirectSolver() override;

    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    void      pattern_changed() override;
    void      operator_changed() override;
    /// The tolerance is not used: the solve is exact up to round-off.
    SolveInfo solve(const NewtonSystem &system, const double tolerance,
                    TrilinosWrappers::MPI::Vector &x, Eigen::VectorXd &y) override;

    /// Counts and wall seconds of the stages since construction.
    struct Statistics
    {
      unsigned int n_symbolic = 0, n_numeric = 0, n_solves = 0;
      double       symbolic_seconds = 0, numeric_seconds = 0, solve_seconds = 0;
    };
    const Statistics &statistics() const { return stats; }

  private:
    /// Ordering and symbolic factorization of A's sparsity pattern.
    void factorize_symbolic(const NewtonSystem &system);
    /// Numeric factorization of A's current values (symbolic first if needed).
    void factorize_numeric(const NewtonSystem &system);
    void report_factorization(const double seconds, const MPI_Comm comm) const;

    std::string solver_type    = "Amesos_Mumps";
    std::string mumps_ordering = "metis";
    bool        verbose        = false;

    std::unique_ptr<Epetra_LinearProblem> problem;
    std::unique_ptr<Amesos_BaseSolver>    solver;
    bool symbolic_done = false, numeric_done = false, schur_done = false;
    /// MUMPS's ICNTL(14): extra working space in percent of its own estimate. MUMPS's
    /// default is 20; the saddle-point block delays pivots, so we start with more margin
    /// (doc/performance.md, working space). Raised (and kept) by workspace_growth when a
    /// factorization runs out of space (INFOG(1) = -8, -9, -14, -15, -17).
    int workspace_percent = initial_workspace_percent;
    static constexpr int initial_workspace_percent = 30;
    /// Each retry analyses again with this many times the margin, at most
    /// max_workspace_retries times (30 % → 7680 %): a shortfall beyond that is no longer
    /// an estimate that was short but a matrix MUMPS cannot factor.
    static constexpr int workspace_growth      = 4;
    static constexpr int max_workspace_retries = 3;
    std::unique_ptr<Epetra_MultiVector> Z;           // A⁻¹B of the current operator
    Eigen::FullPivLU<Eigen::MatrixXd>   schur_lu;    // LU of S = D − C A⁻¹ B
    std::vector<int>                    permutation; // user ordering for MUMPS (1-based)
    Statistics                          stats;
  };
} // namespace fdparticle

#endif
