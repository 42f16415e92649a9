#ifndef fdparticle_solvers_linear_solver_h
#define fdparticle_solvers_linear_solver_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/newton_system.h>

#include <Eigen/Dense>

#include <stdexcept>
#include <string>

namespace fdparticle
{
  using namespace dealii;

  /// A linear solve that could not allocate the memory it needs. Unlike other failures of
  /// a solve, a shorter time step does not help: the time loop stops at once instead of
  /// halving Δt (doc/method.md §5).
  class OutOfMemory : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * The solve of a Newton system for the correction (x, y), whatever the method. The
   * caller says what changed since the last solve, so an implementation keeps what it can:
   *
   *  - pattern_changed(): A's sparsity pattern is about to change (a direct solver drops
   *    its ordering and symbolic factorization, an iterative one its setup);
   *  - operator_changed(): the values of A, B, C, D changed (a direct solver drops its
   *    numeric factorization, an iterative one rebuilds its preconditioner).
   *
   * Nothing else drops them: a Newton solver that reuses its Jacobian simply does not call
   * operator_changed(), and solve() works with the operator it has.
   *
   * Implementations are chosen by create_linear_solver() (linear_solver_factory.h).
   * An implementation may keep references to the system's matrix from one solve to the
   * next (a factorization does): the NewtonSystem must outlive the solver.
   */
  class LinearSolver
  {
  public:
    /// What a solve did: iterations of an iterative method (1 for a direct one) and the
    /// relative residual it reached (0 for a direct one: exact up to round-off, not measured).
    struct SolveInfo
    {
      unsigned int iterations = 0;
      double       residual   = 0;
      /// Iterations of inner solves inside the preconditioner (0 if it has none).
      unsigned int inner_iterations = 0;
      /// This solve factored the matrix (direct) or built the preconditioner (iterative):
      /// the expensive part, which reuse saves.
      bool setup = false;
    };

    virtual ~LinearSolver() = default;

    /// The method in a word ("direct", "iterative"), for the run's first screen line.
    virtual std::string name() const = 0;
    /// Whether solves take iterations (and the tolerance matters).
    virtual bool iterative() const { return false; }

    /// What the solver reads of the system besides A, B, C, D and the residuals; the
    /// assembler builds only what is asked for.
    struct AssembledData
    {
      /// NewtonSystem::Blocks::pressure_mass and pressure_fluid_mass, the cells' pressure
      /// mass matrices (for a Schur complement approximation).
      bool cell_pressure_masses = false;
      /// The velocity block is the program's: A leaves it out, NewtonSystem::Blocks::
      /// velocity_product applies it without a matrix and velocity_inverse inverts it by
      /// the program's geometric multigrid.
      bool matrix_free_velocity_block = false;
    };
    virtual AssembledData assembled_data() const { return {}; }

    /// A's sparsity pattern is about to change: release everything built on it. Must come
    /// before NewtonSystem::reinit() with a new pattern.
    virtual void pattern_changed() = 0;
    /// A, B, C or D have new values.
    virtual void operator_changed() = 0;
    /// Solve [A B; C D][x; y] = −[r_fe; r_p] to the relative tolerance; throws a
    /// std::exception with a sentence when it cannot (OutOfMemory when memory is what
    /// it lacks).
    virtual SolveInfo solve(const NewtonSystem &system, const double tolerance,
                            TrilinosWrappers::MPI::Vector &x, Eigen::VectorXd &y) = 0;
  };
} // namespace fdparticle

#endif
