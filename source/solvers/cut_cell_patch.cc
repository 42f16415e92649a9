#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/cut_cell_patch.h>
#include <fdparticle/solvers/mumps.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Vector.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>

namespace fdparticle
{
  namespace
  {
    /// f(global column, value) for the entries of a local row of M.
    template <typename F>
    void for_each_entry(const Epetra_CrsMatrix &M, const int local_row, const F &f)
    {
      int     n;
      double *v;
      int *   c;
      M.ExtractMyRowView(local_row, n, v, c);
      for (int k = 0; k < n; ++k)
        f(M.GCID64(c[k]), v[k]);
    }
  } // namespace

  CutCellPatch::CutCellPatch() = default;
  CutCellPatch::~CutCellPatch() { clear(); }

  void CutCellPatch::clear()
  {
    factorization.reset();
    matrix.reset();
    rows.reset();
    column_import.reset();
    columns.reset();
    dofs.clear();
    component.clear();
    negated.clear();
    group.clear();
    is_symmetric            = false;
    factored_symmetric_part = false;
    rank_rows.clear();
    rank_offsets.clear();
    patch_rhs.clear();
    local_residual.clear();
    factor_memory = 0;
  }

  std::string CutCellPatch::initialize(const NewtonSystem &system, const unsigned int layers,
                                       const double max_fluid_fraction, const double memory_limit,
                                       const bool symmetric_part)
  {
    clear();
    const MPI_Comm                comm = system.r_fe.get_mpi_communicator();
    std::set<std::pair<int, int>> meeting;
    std::vector<bool>             row_cells;
    find_components(system, grow(system, layers, max_fluid_fraction, meeting, row_cells),
                    meeting);
    if (dealii::Utilities::MPI::sum<unsigned long long>(dofs.size(), comm) == 0)
      return "";
    assemble(system, row_cells);
    return factor(memory_limit, symmetric_part, comm);
  }

  std::vector<int> CutCellPatch::grow(const NewtonSystem &system, const unsigned int layers,
                                      const double                   max_fluid_fraction,
                                      std::set<std::pair<int, int>> &meeting,
                                      std::vector<bool> &            row_cells) const
  {
    using Blocks               = NewtonSystem::Blocks;
    const Epetra_CrsMatrix &E  = system.A.trilinos_matrix();
    const auto &            b  = system.blocks;
    const MPI_Comm          comm  = system.r_fe.get_mpi_communicator();
    const auto &            range = b.range[dealii::Utilities::MPI::this_mpi_process(comm)];
    // This rank's DoFs, numbered locally from 0: u | λ | p (NewtonSystem::Blocks).
    const long long    first = range[0], end = range[Blocks::n_blocks];
    const unsigned int n_local = end - first;
    const unsigned int o_l     = range[Blocks::multiplier] - first;
    const unsigned int o_p     = range[Blocks::pressure] - first;
    const unsigned int npc     = b.pressure_dofs_per_cell;
    const unsigned int n_cells = (end - range[Blocks::pressure]) / npc;
    auto block_of = [&](const unsigned int local) {
      return local < o_l ? Blocks::velocity : local < o_p ? Blocks::multiplier : Blocks::pressure;
    };

    // The particle of each patch DoF and cell; the first particle to reach one keeps it,
    // a second one meets it.
    std::vector<int> label(n_local, -1), cell_label(n_cells, -1);
    auto reach = [&](int &slot, const int particle) {
      if (slot < 0)
        {
          slot = particle;
          return true;
        }
      if (slot != particle)
        meeting.emplace(std::min(slot, particle), std::max(slot, particle));
      return false;
    };

    row_cells.assign(n_cells, false);
    std::vector<unsigned int> new_cells;
    // Seeds: the cells with a particle part whose fluid fraction is at most
    // max_fluid_fraction. That takes the cells inside the particles too: there p and λ are
    // jointly undetermined but for the penalties, and the cheap form of the
    // preconditioner, which does not solve J_w, needs the patch to resolve that pair even
    // where the central cells lie more than a ring away from the cut cells.
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const double fluid = b.cell_fluid_fraction[c];
        if (fluid < 1 && fluid <= max_fluid_fraction)
          {
            Assert(b.cell_particle[c] >= 0, ExcInternalError());
            cell_label[c] = b.cell_particle[c];
            new_cells.push_back(c);
          }
      }

    // f(local column) for the columns of a local row on this rank; the others' columns of
    // block `remote_block` go to their owners with the particle (to_owner), as the patch
    // grows across the partition: a ring around another rank's cells is that rank's to add.
    std::map<unsigned int, std::vector<long long>> to_owner;
    auto row_columns = [&](const unsigned int local, const unsigned int remote_block,
                           const int particle, const auto &f) {
      for_each_entry(E, local, [&](const long long g, double) {
        if (g >= first && g < end)
          f(static_cast<unsigned int>(g - first), particle);
        else if (b.locate(g).first == remote_block)
          {
            auto &list = to_owner[b.owner(g)];
            list.push_back(g);
            list.push_back(particle);
          }
      });
    };
    // f(local DoF, particle) for what other ranks found for this one.
    auto receive = [&](const auto &f) {
      for (const auto &[from, list] : dealii::Utilities::MPI::some_to_some(comm, to_owner))
        for (unsigned int k = 0; k < list.size(); k += 2)
          f(static_cast<unsigned int>(list[k] - first), static_cast<int>(list[k + 1]));
      to_owner.clear();
    };
    for (unsigned int layer = 0;; ++layer)
      {
        // The new cells' pressure DoFs, and the velocity (and multiplier) DoFs they couple to.
        std::vector<unsigned int> new_velocities;
        auto add_velocity = [&](const unsigned int j, const int particle) {
          // With the multiplier DoF at the same node and component.
          if (block_of(j) == Blocks::velocity && reach(label[j], particle))
            {
              label[o_l + j] = particle;
              new_velocities.push_back(j);
            }
        };
        for (const unsigned int c : new_cells)
          for (unsigned int i = 0; i < npc; ++i)
            {
              const unsigned int p = o_p + c * npc + i;
              label[p]             = cell_label[c];
              row_columns(p, Blocks::velocity, cell_label[c], add_velocity);
            }
        receive(add_velocity);
        if (layer == layers)
          {
            if (system.blocks.velocity_product)
              {
                // The cells around the last ring's velocity DoFs: with the patch's own,
                // all that add to its velocity rows.
                auto add_row_cell = [&](const unsigned int j, int) {
                  if (block_of(j) == Blocks::pressure)
                    row_cells[(j - o_p) / npc] = true;
                };
                for (const unsigned int u : new_velocities)
                  row_columns(u, Blocks::pressure, label[u], add_row_cell);
                receive(add_row_cell);
              }
            break;
          }
        new_cells.clear();
        auto add_cell = [&](const unsigned int j, const int particle) {
          if (block_of(j) == Blocks::pressure && reach(cell_label[(j - o_p) / npc], particle))
            new_cells.push_back((j - o_p) / npc);
        };
        for (const unsigned int u : new_velocities)
          row_columns(u, Blocks::pressure, label[u], add_cell);
        receive(add_cell);
      }
    for (unsigned int c = 0; c < n_cells; ++c)
      if (cell_label[c] >= 0)
        row_cells[c] = true;
    return label;
  }

  void CutCellPatch::find_components(const NewtonSystem &                 system,
                                     const std::vector<int> &             label,
                                     const std::set<std::pair<int, int>> &meeting)
  {
    const MPI_Comm comm = system.r_fe.get_mpi_communicator();

    // The components: particles joined where their rings meet on any rank, each named by
    // its smallest particle (the same on every rank).
    int n_labels = 0;
    for (const int l : label)
      n_labels = std::max(n_labels, l + 1);
    n_labels = dealii::Utilities::MPI::max(n_labels, comm);
    std::vector<int> root(n_labels);
    std::iota(root.begin(), root.end(), 0);
    auto find = [&](int l) {
      while (root[l] != l)
        l = root[l] = root[root[l]];
      return l;
    };
    for (const auto &pairs : dealii::Utilities::MPI::all_gather(
           comm, std::vector<std::pair<int, int>>(meeting.begin(), meeting.end())))
      for (const auto &[a, c] : pairs)
        {
          const int ra = find(a), rc = find(c);
          root[std::max(ra, rc)] = std::min(ra, rc);
        }
    for (unsigned int i = 0; i < label.size(); ++i)
      if (label[i] >= 0)
        {
          dofs.push_back(i);
          component.push_back(find(label[i]));
        }
  }

  void CutCellPatch::assemble(const NewtonSystem &system, const std::vector<bool> &row_cells)
  {
    const Epetra_CrsMatrix &E  = system.A.trilinos_matrix();
    const Epetra_Comm &     ec = E.Comm();
    negated.resize(dofs.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
      negated[i] = system.blocks.locate(E.GRID64(dofs[i])).first ==
                   NewtonSystem::Blocks::multiplier;

    // The patch DoFs' rows of A (a local copy: the rows stay with their owners) and how
    // to fetch the entries of a vector at their columns.
    IndexSet owned(system.r_fe.size());
    for (const int i : dofs)
      owned.add_index(E.GRID64(i));
    owned.compress();
    const Epetra_Map    row_map = owned.make_trilinos_map(system.r_fe.get_mpi_communicator(), true);
    const Epetra_Import local(row_map, E.RowMap());
    rows = std::make_unique<Epetra_CrsMatrix>(Copy, row_map, 0);
    rows->Import(E, local, Insert);
    rows->FillComplete(E.DomainMap(), E.RangeMap());
    if (system.blocks.velocity_product)
      {
        // A without its velocity block: the velocity block's entries of the cells around
        // the patch rows, added row by row.
        TrilinosWrappers::SparseMatrix velocity;
        system.blocks.velocity_product->assemble_on_cells(row_cells, velocity);
        Epetra_CrsMatrix velocity_rows(Copy, row_map, 0);
        velocity_rows.Import(velocity.trilinos_matrix(), local, Insert);
        velocity_rows.FillComplete(E.DomainMap(), E.RangeMap());
        auto sum = std::make_unique<Epetra_CrsMatrix>(Copy, row_map, 0);
        std::vector<std::pair<long long, double>> entries;
        std::vector<int>                          cols;
        std::vector<double>                       values;
        for (int r = 0; r < rows->NumMyRows(); ++r)
          {
            // Both rows' entries by column, those of a column summed.
            entries.clear();
            auto add = [&](const long long g, const double v) { entries.emplace_back(g, v); };
            for_each_entry(*rows, r, add);
            for_each_entry(velocity_rows, r, add);
            std::sort(entries.begin(), entries.end(),
                      [](const auto &a, const auto &b) { return a.first < b.first; });
            cols.clear();
            values.clear();
            for (const auto &[g, v] : entries)
              if (!cols.empty() && cols.back() == g)
                values.back() += v;
              else
                {
                  cols.push_back(static_cast<int>(g));
                  values.push_back(v);
                }
            AssertThrow(sum->InsertGlobalValues(row_map.GID(r), cols.size(), values.data(),
                                                cols.data()) == 0,
                        ExcInternalError());
          }
        sum->FillComplete(E.DomainMap(), E.RangeMap());
        rows = std::move(sum);
      }
    column_import = std::make_unique<Epetra_Import>(rows->ColMap(), E.RowMap());
    columns       = std::make_unique<Epetra_Vector>(rows->ColMap());

    // The patch numbers 0 … n − 1, in the order of the ranks and of their DoFs, and the
    // component of every patch DoF, at the columns of the patch rows (−1: not in the
    // patch).
    const Epetra_Map patch_map(-1, static_cast<int>(dofs.size()), 0, ec);
    Epetra_Vector    number(E.RowMap()), part(E.RowMap());
    number.PutScalar(-1);
    for (unsigned int i = 0; i < dofs.size(); ++i)
      {
        number[dofs[i]] = patch_map.GID(i);
        part[dofs[i]]   = component[i];
      }
    // Each multiplier DoF is ordered with the velocity DoF at its node and component
    // (the same local number in its block, and in the patch with it).
    const auto &range = system.blocks.range[dealii::Utilities::MPI::this_mpi_process(
      system.r_fe.get_mpi_communicator())];
    const int   to_velocity = range[NewtonSystem::Blocks::multiplier] - range[0];
    group.resize(dofs.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
      {
        group[i] = patch_map.GID(i);
        if (negated[i])
          {
            const auto u = std::lower_bound(dofs.begin(), dofs.end(), dofs[i] - to_velocity);
            if (u != dofs.end() && *u == dofs[i] - to_velocity)
              group[i] = patch_map.GID(u - dofs.begin());
          }
      }
    Epetra_Vector column_number(rows->ColMap()), column_part(rows->ColMap());
    column_number.Import(number, *column_import, Insert);
    column_part.Import(part, *column_import, Insert);

    matrix = std::make_unique<Epetra_CrsMatrix>(Copy, patch_map, 0);
    std::vector<int>    cols;
    std::vector<double> values;
    for (int r = 0; r < rows->NumMyRows(); ++r)
      {
        int     n;
        double *v;
        int *   c;
        rows->ExtractMyRowView(r, n, v, c);
        cols.clear();
        values.clear();
        for (int k = 0; k < n; ++k)
          if (column_number[c[k]] >= 0 && column_part[c[k]] == component[r])
            {
              cols.push_back(static_cast<int>(column_number[c[k]]));
              values.push_back(negated[r] ? -v[k] : v[k]);
            }
        AssertThrow(matrix->InsertGlobalValues(patch_map.GID(r), cols.size(), values.data(),
                                               cols.data()) == 0,
                    ExcInternalError());
      }
    AssertThrow(matrix->FillComplete() == 0, ExcInternalError());
  }

  std::string CutCellPatch::factor(const double memory_limit, const bool symmetric_part,
                                   const MPI_Comm comm)
  {
    // MUMPS reads the ordering during its analysis only.
    std::vector<int>         ordering = mumps::nested_dissection(*matrix, comm, group);
    group.clear();
    const unsigned long long n        = matrix->NumGlobalRows64();
    auto why = [&](const std::string &reason) {
      clear();
      return reason;
    };
    is_symmetric            = test_symmetry();
    factored_symmetric_part = !is_symmetric && symmetric_part;
    // This rank's entries of the patch matrix (of a symmetric one its lower triangle; for
    // the symmetric part of another, half of each off-diagonal entry at its place in the
    // lower triangle, where MUMPS sums the halves of a_ij and a_ji), numbered over all
    // ranks.
    std::vector<int>    entry_rows, entry_columns;
    std::vector<double> entry_values;
    entry_rows.reserve(matrix->NumMyNonzeros());
    entry_columns.reserve(matrix->NumMyNonzeros());
    entry_values.reserve(matrix->NumMyNonzeros());
    for (int r = 0; r < matrix->NumMyRows(); ++r)
      {
        const int row = matrix->GRID(r);
        for_each_entry(*matrix, r, [&](const long long g, const double v) {
          if (factored_symmetric_part)
            {
              entry_rows.push_back(std::max<int>(row, g));
              entry_columns.push_back(std::min<int>(row, g));
              entry_values.push_back(g == row ? v : 0.5 * v);
            }
          else if (!is_symmetric || g <= row)
            {
              entry_rows.push_back(row);
              entry_columns.push_back(static_cast<int>(g));
              entry_values.push_back(v);
            }
        });
      }
    const int my_rows = matrix->NumMyRows();
    matrix.reset();

    factorization = std::make_unique<mumps::Factorization>(comm, n,
                                                           is_symmetric || factored_symmetric_part,
                                                           std::move(entry_rows),
                                                           std::move(entry_columns),
                                                           std::move(entry_values));
    for (int attempt = 0, workspace = mumps::initial_workspace_percent;; ++attempt)
      {
        const int analysis = factorization->analyse(ordering, workspace);
        if (analysis < 0)
          return why("MUMPS's analysis failed (INFOG(1) = " + std::to_string(analysis) + ")");
        const double estimate = factorization->estimated_memory();
        if (memory_limit > 0 && estimate > memory_limit)
          {
            std::ostringstream s;
            s << std::setprecision(2) << "its " << n << " unknowns would need about "
              << estimate / 1e9 << " GB on one rank to factor, more than the "
              << memory_limit / 1e9 << " GB allowed";
            return why(s.str());
          }
        const int info = factorization->factor();
        if (info >= 0)
          break;
        if (!mumps::short_of_workspace(info) || attempt == mumps::max_workspace_retries)
          return why(info == mumps::singular      ? "MUMPS found it singular" :
                     info == mumps::out_of_memory ? "MUMPS could not allocate its factors" :
                                                    "MUMPS's INFOG(1) = " + std::to_string(info));
        workspace *= mumps::workspace_growth;
      }
    factor_memory = factorization->memory();

    const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
    rank_rows.resize(root ? dealii::Utilities::MPI::n_mpi_processes(comm) : 0);
    MPI_Gather(&my_rows, 1, MPI_INT, rank_rows.data(), 1, MPI_INT, 0, comm);
    rank_offsets.assign(rank_rows.size(), 0);
    for (unsigned int p = 1; p < rank_rows.size(); ++p)
      rank_offsets[p] = rank_offsets[p - 1] + rank_rows[p - 1];
    patch_rhs.resize(root ? n : 0);
    local_residual.resize(my_rows);
    return "";
  }

  bool CutCellPatch::test_symmetry() const
  {
    const Epetra_Map &map = matrix->RowMap();
    Epetra_Vector     x(map), y(map), Mx(map), My(map);
    // Scattered over [−½, ½) by the fractional parts of multiples of two irrationals.
    for (int i = 0; i < map.NumMyElements(); ++i)
      {
        const double g = map.GID64(i);
        x[i]           = g * 0.6180339887498949 - std::floor(g * 0.6180339887498949) - 0.5;
        y[i]           = g * 0.7548776662466927 - std::floor(g * 0.7548776662466927) - 0.5;
      }
    matrix->Multiply(false, x, Mx);
    matrix->Multiply(false, y, My);
    double x_My, y_Mx, x_norm, y_norm, Mx_norm, My_norm;
    x.Dot(My, &x_My);
    y.Dot(Mx, &y_Mx);
    x.Norm2(&x_norm);
    y.Norm2(&y_norm);
    Mx.Norm2(&Mx_norm);
    My.Norm2(&My_norm);
    return std::abs(x_My - y_Mx) <= 1e-12 * (x_norm * My_norm + y_norm * Mx_norm);
  }

  void CutCellPatch::add_correction(TrilinosWrappers::MPI::Vector &      x,
                                    const TrilinosWrappers::MPI::Vector &r) const
  {
    // r − A x on the patch rows only (their rows of A are this rank's).
    columns->Import(x.trilinos_vector(), *column_import, Insert);
    const double *xc = columns->Values();
    const double *rv = r.trilinos_vector().Values();
    double *      ri = local_residual.data();
    for (unsigned int i = 0; i < dofs.size(); ++i)
      {
        int     n;
        double *v;
        int *   c;
        rows->ExtractMyRowView(i, n, v, c);
        ri[i] = rv[dofs[i]];
        for (int k = 0; k < n; ++k)
          ri[i] -= v[k] * xc[c[k]];
        if (negated[i])
          ri[i] = -ri[i];
      }
    const MPI_Comm comm = x.get_mpi_communicator();
    MPI_Gatherv(local_residual.data(), dofs.size(), MPI_DOUBLE, patch_rhs.data(),
                rank_rows.data(), rank_offsets.data(), MPI_DOUBLE, 0, comm);
    AssertThrow(factorization->solve(patch_rhs) >= 0,
                ExcMessage("MUMPS failed to solve with the factored cut-cell patch."));
    MPI_Scatterv(patch_rhs.data(), rank_rows.data(), rank_offsets.data(), MPI_DOUBLE,
                 local_residual.data(), dofs.size(), MPI_DOUBLE, 0, comm);
    double *xv = x.trilinos_vector().Values();
    for (unsigned int i = 0; i < dofs.size(); ++i)
      xv[dofs[i]] += local_residual[i];
  }
} // namespace fdparticle
