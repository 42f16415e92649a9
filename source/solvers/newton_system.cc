#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/newton_system.h>

#include <Epetra_CrsGraph.h>

#include <algorithm>
#include <cmath>

namespace fdparticle
{
  unsigned int NewtonSystem::Blocks::owner(const types::global_dof_index g) const
  {
    // The last rank whose range starts at or before g (ranks may own nothing).
    auto it = std::upper_bound(range.begin(), range.end(), g,
                               [](const types::global_dof_index x, const auto &r) { return x < r[0]; });
    Assert(it != range.begin(), ExcInternalError());
    return (it - range.begin()) - 1;
  }

  std::pair<unsigned int, types::global_dof_index>
  NewtonSystem::Blocks::locate(const types::global_dof_index g) const
  {
    const unsigned int r = owner(g);
    unsigned int       b = 0;
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

  std::vector<long long> NewtonSystem::sorted_columns(const Epetra_CrsGraph &graph, const int r)
  {
    int  length;
    int *local_columns;
    graph.ExtractMyRowView(r, length, local_columns);
    std::vector<long long> columns(length);
    for (int k = 0; k < length; ++k)
      columns[k] = graph.GCID64(local_columns[k]);
    std::sort(columns.begin(), columns.end());
    return columns;
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
      same = now.NumMyIndices(r) == next.NumMyIndices(r) &&
             sorted_columns(now, r) == sorted_columns(next, r);
    return Utilities::MPI::min(same ? 1 : 0, sparsity.get_mpi_communicator()) == 1;
  }

  types::global_dof_index NewtonSystem::velocity_block_nonzeros() const
  {
    const Epetra_CrsGraph &graph = A.trilinos_matrix().Graph();
    types::global_dof_index count = 0;
    for (int r = 0; r < graph.NumMyRows(); ++r)
      if (blocks.locate(graph.GRID64(r)).first == Blocks::velocity)
        {
          int  length;
          int *columns;
          graph.ExtractMyRowView(r, length, columns);
          for (int k = 0; k < length; ++k)
            count += blocks.locate(graph.GCID64(columns[k])).first == Blocks::velocity;
        }
    return Utilities::MPI::sum(count, r_fe.get_mpi_communicator());
  }

  IndexSet NewtonSystem::particle_unknowns(const unsigned int m, const MPI_Comm comm)
  {
    IndexSet unknowns(m);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      unknowns.add_range(0, m);
    return unknowns;
  }

  TrilinosWrappers::SparsityPattern NewtonSystem::border_pattern(const IndexSet &   owned,
                                                                 const IndexSet &   relevant,
                                                                 const unsigned int m,
                                                                 const MPI_Comm     comm)
  {
    // Without particle unknowns, the empty pattern: B and Cᵀ stay unallocated.
    if (m == 0)
      return TrilinosWrappers::SparsityPattern();
    return TrilinosWrappers::SparsityPattern(owned, particle_unknowns(m, comm), relevant, comm);
  }

  void NewtonSystem::reinit(const IndexSet &                         owned,
                            const IndexSet &                         relevant,
                            const TrilinosWrappers::SparsityPattern &sparsity,
                            const bool                               new_pattern,
                            const TrilinosWrappers::SparsityPattern &border,
                            const MPI_Comm                           comm)
  {
    if (new_pattern)
      A.reinit(sparsity);
    else
      A = 0;
    // Writable ghost entries: cells at a partition boundary add into DoFs owned by a
    // neighbour, and compress(add) ships them there.
    r_fe.reinit(owned, relevant, comm, /*vector_writable=*/true);
    const unsigned int m = border.n_cols();
    if (m > 0)
      {
        B.reinit(border);
        C_transposed.reinit(border);
        Assert(B.trilinos_matrix().RowMap().SameAs(r_fe.trilinos_vector().Map()),
               ExcMessage("B's rows must be numbered locally as r_fe's entries."));
      }
    else
      {
        B.clear();
        C_transposed.clear();
      }
    border_rows.clear();
    D.resize(m, m);
    r_p.setZero(m);
  }

  void NewtonSystem::compress_border(const VectorOperation::values op)
  {
    border_rows.clear();
    if (B.m() == 0)
      return;
    B.compress(op);
    C_transposed.compress(op);
    const Epetra_CrsMatrix &b = B.trilinos_matrix(), &c = C_transposed.trilinos_matrix();
    Assert(b.RowMap().SameAs(c.RowMap()), ExcInternalError());
    for (int r = 0; r < b.NumMyRows(); ++r)
      if (b.NumMyEntries(r) > 0 || c.NumMyEntries(r) > 0)
        border_rows.push_back(r);
  }

  void NewtonSystem::zero(const bool with_matrix)
  {
    r_fe = 0;
    r_p.setZero();
    if (!with_matrix)
      return;
    A = 0;
    if (B.m() > 0)
      {
        B = 0;
        C_transposed = 0;
      }
    D.setZero();
  }

  double NewtonSystem::residual_norm() const
  {
    return std::sqrt(r_fe.norm_sqr() + r_p.squaredNorm());
  }

  void NewtonSystem::add_border(const Eigen::VectorXd &y, TrilinosWrappers::MPI::Vector &x) const
  {
    AssertDimension(y.size(), n_particle_unknowns());
    double *xv = x.trilinos_vector()[0];
    for_each_border_entry(B,
                          [&](const int r, const unsigned int j, const double v) { xv[r] += v * y[j]; });
  }

  Eigen::VectorXd NewtonSystem::border_product(const TrilinosWrappers::MPI::Vector &x) const
  {
    std::vector<double> g(n_particle_unknowns(), 0.0);
    const double *      xv = x.trilinos_vector()[0];
    for_each_border_entry(C_transposed,
                          [&](const int r, const unsigned int i, const double v) { g[i] += v * xv[r]; });
    Utilities::MPI::sum(g, r_fe.get_mpi_communicator(), g);
    return Eigen::Map<const Eigen::VectorXd>(g.data(), g.size());
  }
} // namespace fdparticle
