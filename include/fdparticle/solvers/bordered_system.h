#ifndef fdparticle_solvers_bordered_system_h
#define fdparticle_solvers_bordered_system_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

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
   * The Newton system as a 2×2 block matrix
   *
   *     [ A  B ] [ x ]   [ f ]      A: (u, λ, p) finite-element block (Trilinos, distributed)
   *     [ C  D ] [ y ] = [ g ]      y: the particle block (V_k, ω_k), m = (dim + rot)·n_free
   *
   * The particle block has rank m ≤ 6 per particle, so B is kept as m distributed columns,
   * C as m distributed rows and D as a small dense (Eigen) matrix, replicated on every rank.
   * solve() factors A (Amesos: MUMPS in parallel, or KLU) and eliminates y through the
   * m×m Schur complement S = D − C A⁻¹ B, at the price of one solve with m + 1 right-hand
   * sides for the first Newton correction with a Jacobian; A⁻¹B and S stay with the
   * Jacobian, so later corrections with it (modified Newton) need one right-hand side.
   *
   * The factorization has two stages with their own entry points: the symbolic one
   * (ordering, analysis) depends only on A's sparsity pattern and is kept until reinit();
   * the numeric one depends on A's values and is dropped by zero(true). A caller that keeps
   * the pattern from one Jacobian to the next (reinit() not called) pays the symbolic stage
   * once.
   */
  class BorderedSystem
  {
  public:
    BorderedSystem();
    ~BorderedSystem();

    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    void reinit(const IndexSet &locally_owned, const IndexSet &locally_relevant,
                const TrilinosWrappers::SparsityPattern &sparsity,
                const MPI_Comm comm, const unsigned int n_particle_unknowns);

    /// Zero A, B, C, D and the residuals (matrix parts only if with_matrix).
    void zero(const bool with_matrix);

    /// Solve [A B; C D][x; y] = −[r_fe; r_p], the Newton correction. Factors A first if
    /// its current values are not factored yet.
    void solve_newton_step(TrilinosWrappers::MPI::Vector &x, Eigen::VectorXd &y);

    /// Ordering and symbolic factorization of A's sparsity pattern (done by
    /// solve_newton_step() when needed; kept until reinit()).
    void factorize_symbolic();

    /// Numeric factorization of A's current values (done by solve_newton_step() when
    /// needed; kept until zero(true)). Runs factorize_symbolic() first if needed.
    void factorize_numeric();

    /// 2-norm of the residual (r_fe; r_p).
    double residual_norm() const;

    unsigned int n_particle_unknowns() const { return B.size(); }

    /// Counts and wall seconds of the direct solver's stages since construction.
    struct DirectSolverStatistics
    {
      unsigned int n_symbolic = 0, n_numeric = 0, n_solves = 0;
      double       symbolic_seconds = 0, numeric_seconds = 0, solve_seconds = 0;
    };
    const DirectSolverStatistics &direct_solver_statistics() const { return stats; }

    TrilinosWrappers::SparseMatrix             A;
    std::vector<TrilinosWrappers::MPI::Vector> B, C;
    Eigen::MatrixXd                            D;
    TrilinosWrappers::MPI::Vector              r_fe;
    Eigen::VectorXd                            r_p;

  private:
    void release_factorization();
    bool same_pattern(const TrilinosWrappers::SparsityPattern &sparsity) const;
    void report_factorization(const double seconds) const;

    std::string solver_type    = "Amesos_Mumps";
    std::string mumps_ordering = "metis";
    bool        verbose        = false;

    std::unique_ptr<Epetra_LinearProblem> problem;
    std::unique_ptr<Amesos_BaseSolver>    solver;
    bool symbolic_done = false, numeric_done = false, schur_done = false;
    /// MUMPS's ICNTL(14): extra working space in percent of its own estimate. Raised (and
    /// kept) when a factorization runs out of it (INFOG(1) = -8, -9, -14, -15, -17).
    int workspace_percent = 30;
    std::unique_ptr<Epetra_MultiVector>   Z;        // A⁻¹B of the current Jacobian
    Eigen::FullPivLU<Eigen::MatrixXd>     schur_lu; // LU of S = D − C A⁻¹ B
    std::vector<int>                      permutation; // user ordering for MUMPS (1-based)
    DirectSolverStatistics                stats;
  };
} // namespace fdparticle

#endif
