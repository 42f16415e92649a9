#ifndef fdparticle_solvers_newton_system_h
#define fdparticle_solvers_newton_system_h

#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Eigen/Dense>

#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The Newton system of one iteration as a 2×2 block matrix (doc/method.md §5)
   *
   *     [ A  B ] [ x ]     [ r_fe ]   A: (u, λ, p) finite-element block (Trilinos, distributed)
   *     [ C  D ] [ y ] = − [ r_p  ]   y: the particle block (V_k, ω_k), m = (dim + rot)·n_free
   *
   * The particle block has rank m ≤ 6 per particle, so B is kept as m distributed columns,
   * C as m distributed rows and D as a small dense (Eigen) matrix, replicated on every rank.
   *
   * Storage only: the assembler and the particle interactions write into it, a LinearSolver
   * reads it. The blocks are public members, as the finite-element assembly writes A, B, C
   * and r_fe entry by entry through AffineConstraints.
   */
  class NewtonSystem
  {
  public:
    /// Whether A already has this sparsity pattern (same rows on every rank, same global
    /// columns in every row). Collective.
    bool has_pattern(const TrilinosWrappers::SparsityPattern &sparsity) const;

    /// Lay out the system for a step: A gets the pattern (rebuilt only if new_pattern, else
    /// zeroed), the residual and the border vectors B, C the layout of the owned and
    /// relevant DoFs, D and r_p the size m of the particle unknowns.
    void reinit(const IndexSet &locally_owned, const IndexSet &locally_relevant,
                const TrilinosWrappers::SparsityPattern &sparsity, const bool new_pattern,
                const MPI_Comm comm, const unsigned int m);

    /// Zero the residuals, and A, B, C, D too if with_matrix.
    void zero(const bool with_matrix);

    /// 2-norm of the residual (r_fe; r_p).
    double residual_norm() const;

    TrilinosWrappers::SparseMatrix             A;
    std::vector<TrilinosWrappers::MPI::Vector> B, C;
    Eigen::MatrixXd                            D;
    TrilinosWrappers::MPI::Vector              r_fe;
    Eigen::VectorXd                            r_p;
  };
} // namespace fdparticle

#endif
