#ifndef fdparticle_bordered_system_h
#define fdparticle_bordered_system_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Eigen/Dense>

#include <memory>
#include <string>
#include <vector>

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
   * solve() factors A once (Amesos: MUMPS in parallel, or KLU) and eliminates y through the
   * m×m Schur complement S = D − C A⁻¹ B, at the price of m + 1 triangular solves.
   */
  class BorderedSystem
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    void reinit(const IndexSet &locally_owned, const IndexSet &locally_relevant,
                const TrilinosWrappers::SparsityPattern &sparsity,
                const MPI_Comm comm, const unsigned int n_particle_unknowns);

    /// Zero A, B, C, D and the residuals (matrix parts only if with_matrix).
    void zero(const bool with_matrix);

    /// Solve [A B; C D][x; y] = −[r_fe; r_p], the Newton correction.
    void solve_newton_step(TrilinosWrappers::MPI::Vector &x, Eigen::VectorXd &y);

    /// 2-norm of the residual (r_fe; r_p).
    double residual_norm() const;

    unsigned int n_particle_unknowns() const { return B.size(); }

    TrilinosWrappers::SparseMatrix             A;
    std::vector<TrilinosWrappers::MPI::Vector> B, C;
    Eigen::MatrixXd                            D;
    TrilinosWrappers::MPI::Vector              r_fe;
    Eigen::VectorXd                            r_p;

  private:
    std::string                                   solver_type = "Amesos_Mumps";
    SolverControl                                 control;
    std::unique_ptr<TrilinosWrappers::SolverDirect> direct;
  };
} // namespace fdparticle

#endif
