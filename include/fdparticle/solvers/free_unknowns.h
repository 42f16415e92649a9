#ifndef fdparticle_solvers_free_unknowns_h
#define fdparticle_solvers_free_unknowns_h

#include <fdparticle/solvers/bordered_operator.h>

#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The unknowns the Krylov methods of IterativeSolver iterate on: the owned
   * finite-element DoFs that no constraint of the Newton correction fixes, and the
   * particle unknowns. A correction is zero at the constrained DoFs (inactive multipliers,
   * walls, hanging nodes, periodic faces; NewtonSystem::Blocks::free_dofs) until the
   * constraints are distributed, and A couples them to nothing but their own diagonal, so
   * the Krylov vectors leave them out: about half of the sediment step's unknowns are
   * inactive multipliers (doc/scaling.md, where the memory goes).
   *
   * An operator or preconditioner that works on BorderedOperator's layout acts on these
   * vectors through vmult(), which widens its argument with zeros and keeps the free part
   * of its result.
   */
  class FreeUnknowns
  {
  public:
    using BlockVector = BorderedOperator::BlockVector;

    /// op and system must outlive this object, and free_dofs (local numbers of the owned
    /// DoFs, ascending) must not change while it lives. Collective.
    FreeUnknowns(const BorderedOperator &op, const NewtonSystem &system);

    /// v laid out for the free unknowns, zero.
    void reinit_vector(BlockVector &v) const;

    /// The free part of full (BorderedOperator's layout) into v.
    void restrict(const BlockVector &full, BlockVector &v) const;
    /// v into BorderedOperator's layout; full must be zero at the constrained DoFs (as
    /// BorderedOperator::reinit_vector makes it and this leaves it).
    void extend(const BlockVector &v, BlockVector &full) const;

    /// dst = R M Rᵀ src for an M acting on BorderedOperator's layout (the operator or a
    /// preconditioner), R the restriction to the free unknowns.
    template <typename Operator>
    void vmult(const Operator &M, BlockVector &dst, const BlockVector &src) const
    {
      extend(src, wide_src);
      M.vmult(wide_dst, wide_src);
      restrict(wide_dst, dst);
    }

    /// Unknowns of the full layout over all ranks, and the free ones.
    types::global_dof_index n_full() const { return n_all; }
    types::global_dof_index n_free() const { return layout.size(); }

  private:
    const BorderedOperator &         op;
    const std::vector<unsigned int> &free_dofs;
    /// This rank's part of the free unknowns' numbering.
    IndexSet                layout;
    types::global_dof_index n_all;
    /// Full-layout work vectors: wide_src is zero at the constrained DoFs throughout.
    mutable BlockVector wide_src, wide_dst;
  };

  /// An operator or preconditioner on BorderedOperator's layout seen through
  /// FreeUnknowns, for deal.II's solvers.
  template <typename Operator>
  struct OnFreeUnknowns
  {
    const FreeUnknowns &free;
    const Operator &    M;
    void vmult(FreeUnknowns::BlockVector &dst, const FreeUnknowns::BlockVector &src) const
    {
      free.vmult(M, dst, src);
    }
  };
} // namespace fdparticle

#endif
