#ifndef fdparticle_solvers_direct_solver_h
#define fdparticle_solvers_direct_solver_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/linear_solver.h>
#include <fdparticle/solvers/mumps.h>
#include <fdparticle/solvers/newton_system.h>

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

class Amesos_BaseSolver;
class Epetra_LinearProblem;
class Epetra_CrsMatrix;
class Epetra_MultiVector;

namespace fdparticle
{
  using namespace dealii;

  /**
   * The Newton system solved by a sparse direct factorization (Amesos: MUMPS in parallel,
   * or KLU), in one of two ways by the number m of particle unknowns (doc/method.md §8):
   *
   * - m ≤ max_schur_unknowns: factor A and eliminate the particle unknowns through the
   *   m×m Schur complement S = D − C A⁻¹ B. The first solve with an operator costs one
   *   solve with m + 1 right-hand sides; A⁻¹B and S stay with the operator, so later
   *   solves with it (modified Newton) need one right-hand side.
   * - m > max_schur_unknowns: factor the whole bordered matrix K = [A B; C D], the
   *   particle unknowns numbered after the finite-element DoFs and owned by rank 0, each
   *   coupled only to the DoFs where its column of B and row of C are non-zero (the cells
   *   of its ball). One right-hand side, whatever the number of particles.
   *
   * The factorization has two stages: the symbolic one (ordering, analysis) depends only on
   * the factored matrix's sparsity pattern (A's, and for K the particles' couplings too) and
   * is kept while it stays the same; the numeric one depends on the values and is kept
   * until operator_changed(). Both are done by solve() when needed.
   */
  class DirectSolver : public LinearSolver
  {
  public:
    DirectSolver();
    ~DirectSolver() override;

    static void declare_parameters(ParameterHandler &prm);
    /// dim picks the ordering 'MUMPS ordering = default' stands for.
    void        parse_parameters(ParameterHandler &prm, const unsigned int dim);

    std::string name() const override { return "direct"; }
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
    /// The MUMPS ordering in use ('default' resolved).
    const std::string &ordering() const { return mumps_ordering; }

  private:
    /**
     * Particle unknowns up to which the Schur complement is used. Its cost is m solves per
     * new Jacobian; K's is a new analysis whenever a particle's cells change (every step
     * on a moving particle) and a copy of A. The two cost the same near m = 12–18 (two
     * spheres in 3D, four disks in 2D; doc/method.md §8).
     */
    static constexpr unsigned int max_schur_unknowns = 12;

    /// Build K from the blocks of system; a new K (and a new analysis) only if its pattern
    /// differs from the previous K's on some rank. Collective.
    void assemble_bordered(const NewtonSystem &system);
    /// Ordering and symbolic factorization of the factored matrix's sparsity pattern.
    void factorize_symbolic(const MPI_Comm comm);
    /// Numeric factorization of its current values (symbolic first if needed).
    void factorize_numeric(const MPI_Comm comm);
    /// sol = (factored matrix)⁻¹ rhs, timed and counted.
    void forward_backward(Epetra_MultiVector &rhs, Epetra_MultiVector &sol, const MPI_Comm comm);
    /// The two ways of solve(), after the factorization.
    SolveInfo solve_by_schur(const NewtonSystem &system, TrilinosWrappers::MPI::Vector &x,
                             Eigen::VectorXd &y);
    SolveInfo solve_bordered(const NewtonSystem &system, TrilinosWrappers::MPI::Vector &x,
                             Eigen::VectorXd &y);
    void report_factorization(const double seconds, const MPI_Comm comm) const;

    std::string solver_type    = "Amesos_Mumps";
    std::string mumps_ordering = "metis";
    bool        verbose        = false;
    /// Largest memory the MUMPS factorization may need on one rank, in MB, by its
    /// analysis' estimate (0: no limit).
    double memory_limit_mb = 0;

    std::unique_ptr<Epetra_LinearProblem> problem;
    std::unique_ptr<Amesos_BaseSolver>    solver;
    bool symbolic_done = false, numeric_done = false, schur_done = false;
    /// The matrix the factorization refers to: A's Epetra matrix or K.
    const Epetra_CrsMatrix *factored = nullptr;
    /// K = [A B; C D]; rows of A where each rank owns them, particle rows on rank 0.
    std::unique_ptr<Epetra_CrsMatrix> K;
    /// MUMPS's ICNTL(14), raised (and kept) when a factorization runs out of working
    /// space (mumps::initial_workspace_percent).
    int workspace_percent = mumps::initial_workspace_percent;
    std::unique_ptr<Epetra_MultiVector> Z;           // A⁻¹B of the current operator
    Eigen::FullPivLU<Eigen::MatrixXd>   schur_lu;    // LU of S = D − C A⁻¹ B
    std::vector<int>                    permutation; // user ordering for MUMPS (1-based)
    Statistics                          stats;
  };
} // namespace fdparticle

#endif
