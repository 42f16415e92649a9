#ifndef fdparticle_solvers_bordered_operator_h
#define fdparticle_solvers_bordered_operator_h

#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_parallel_block_vector.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/newton_system.h>

#include <Eigen/Dense>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The Newton matrix [A B; C D] of a NewtonSystem (doc/method.md §8) as an operator on
   * block vectors for a Krylov method: block 0 holds the finite-element unknowns in A's
   * layout, block 1 the m particle unknowns, all owned by rank 0 (m is small; every rank
   * needs all of them for B y, and one broadcast gives them). Where A leaves out the
   * velocity block, NewtonSystem::Blocks::velocity_product adds it.
   */
  class BorderedOperator
  {
  public:
    using BlockVector = TrilinosWrappers::MPI::BlockVector;

    /// The system must outlive the operator; its layout (A, B, C, D) must not change.
    explicit BorderedOperator(const NewtonSystem &system);

    /// v laid out for this operator, zero.
    void reinit_vector(BlockVector &v) const;

    /// The layout of the particle block: all on rank 0.
    const IndexSet &particle_layout() const { return particle_dofs; }

    /// dst = [A B; C D] src.
    void vmult(BlockVector &dst, const BlockVector &src) const;

    /// The particle block of v, on every rank.
    Eigen::VectorXd particle_part(const BlockVector &v) const;
    /// Write y into the particle block of v (on rank 0, which owns it).
    void set_particle_part(BlockVector &v, const Eigen::VectorXd &y) const;

    unsigned int n_particle_unknowns() const { return system.n_particle_unknowns(); }

    /// Wall time of all vmult calls so far (this rank's, s).
    double vmult_time() const { return vmult_seconds; }

  private:
    const NewtonSystem &system;
    /// The particle unknowns' layout: all on rank 0.
    IndexSet particle_dofs;
    mutable double vmult_seconds = 0;
  };
} // namespace fdparticle

#endif
