#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/newton_system.h>

#include <Epetra_CrsGraph.h>

#include <algorithm>
#include <cmath>

namespace fdparticle
{
  std::pair<unsigned int, types::global_dof_index>
  NewtonSystem::Blocks::locate(const types::global_dof_index g) const
  {
    // The last rank whose range starts at or before g (ranks may own nothing).
    auto it = std::upper_bound(range.begin(), range.end(), g,
                               [](const types::global_dof_index x, const auto &r) { return x < r[0]; });
    Assert(it != range.begin(), ExcInternalError());
    const std::size_t r = (it - range.begin()) - 1;
    unsigned int      b = 0;
    while (b + 1 < n_blocks && g >= range[r][b + 1])
      ++b;
    return {b, offset[r][b] + (g - range[r][b])};
  }

  types::global_dof_index NewtonSystem::Blocks::size(const unsigned int b) const
  {
    const std::size_t last = range.size() - 1;
    return offset[last][b] + (range[last][b + 1] - range[last][b]);
  }

  IndexSet NewtonSystem::Blocks::global_dofs(const unsigned int b) const
  {
    IndexSet dofs(range.empty() ? 0 : range.back()[n_blocks]);
    for (const auto &r : range)
      dofs.add_range(r[b], r[b + 1]);
    dofs.compress();
    return dofs;
  }

  bool NewtonSystem::has_pattern(const TrilinosWrappers::SparsityPattern &sparsity) const
  {
    if (A.m() == 0)
      return false;
    const Epetra_CrsGraph &now  = A.trilinos_matrix().Graph();
    const Epetra_CrsGraph &next = sparsity.trilinos_sparsity_pattern();
    bool same = now.RowMap().SameAs(next.RowMap()) && now.NumMyRows() == next.NumMyRows() &&
                now.NumMyNonzeros() == next.NumMyNonzeros();
    for (int r = 0; same && r < now.NumMyRows(); ++r)
      {
        int  n_now, n_next;
        int *c_now, *c_next;
        now.ExtractMyRowView(r, n_now, c_now);
        next.ExtractMyRowView(r, n_next, c_next);
        same = n_now == n_next;
        // Compare global column indices, sorted (the local numbering of the columns may
        // differ between the two graphs).
        std::vector<long long> a(n_now), b(n_next);
        for (int k = 0; same && k < n_now; ++k)
          {
            a[k] = now.GCID64(c_now[k]);
            b[k] = next.GCID64(c_next[k]);
          }
        std::sort(a.begin(), a.end());
        std::sort(b.begin(), b.end());
        same = same && a == b;
      }
    return Utilities::MPI::min(same ? 1 : 0, sparsity.get_mpi_communicator()) == 1;
  }

  void NewtonSystem::reinit(const IndexSet &                         owned,
                            const IndexSet &                         relevant,
                            const TrilinosWrappers::SparsityPattern &sparsity,
                            const bool                               new_pattern,
                            const MPI_Comm                           comm,
                            const unsigned int                       m)
  {
    if (new_pattern)
      A.reinit(sparsity);
    else
      A = 0;
    // Writable ghost entries: cells at a partition boundary add into DoFs owned by a
    // neighbour, and compress(add) ships them there.
    r_fe.reinit(owned, relevant, comm, /*vector_writable=*/true);
    // Fresh copies, not assignment: assigning a Trilinos vector to one whose old layout has
    // the same size and local range imports into that old layout, and after a mesh
    // adaptation in parallel the owned index sets can differ with equal ranges, so the
    // border vectors would keep the previous partition.
    B = std::vector<TrilinosWrappers::MPI::Vector>(m, r_fe);
    C = std::vector<TrilinosWrappers::MPI::Vector>(m, r_fe);
    D.setZero(m, m);
    r_p.setZero(m);
  }

  void NewtonSystem::zero(const bool with_matrix)
  {
    r_fe = 0;
    r_p.setZero();
    if (!with_matrix)
      return;
    A = 0;
    for (auto &b : B)
      b = 0;
    for (auto &c : C)
      c = 0;
    D.setZero();
  }

  double NewtonSystem::residual_norm() const
  {
    return std::sqrt(r_fe.norm_sqr() + r_p.squaredNorm());
  }
} // namespace fdparticle
