#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/cut_cell_patch.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Vector.h>
#include <umfpack.h>

#include <algorithm>
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

  CutCellPatch::~CutCellPatch() { clear(); }

  void CutCellPatch::clear()
  {
    dofs.clear();
    component.clear();
    import.reset();
    residual.reset();
    correction.reset();
    rows.reset();
    column_import.reset();
    columns.reset();
    if (numeric != nullptr)
      umfpack_di_free_numeric(&numeric);
    factor_memory = 0;
    matrix        = Eigen::SparseMatrix<double>();
  }

  std::string CutCellPatch::initialize(const NewtonSystem &system, const unsigned int layers,
                                       const double max_fluid_fraction, const double memory_limit)
  {
    clear();
    std::set<std::pair<int, int>> meeting;
    const std::vector<int> label = grow(system, layers, max_fluid_fraction, meeting);
    assemble(system, distribute(system, label, meeting));
    return dofs.empty() ? "" : factor(memory_limit);
  }

  std::vector<int> CutCellPatch::grow(const NewtonSystem &system, const unsigned int layers,
                                      const double                   max_fluid_fraction,
                                      std::set<std::pair<int, int>> &meeting) const
  {
    using Blocks               = NewtonSystem::Blocks;
    const Epetra_CrsMatrix &E  = system.A.trilinos_matrix();
    const auto &            b  = system.blocks;
    const MPI_Comm          comm  = system.r_fe.get_mpi_communicator();
    const auto &            range = b.range[Utilities::MPI::this_mpi_process(comm)];
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

    std::vector<unsigned int> new_cells;
    // Seeds: the cells with a particle part whose fluid part is at most
    // max_fluid_fraction of the cell (the pressure mass over the fluid part sums the same
    // terms as the whole where all points are fluid, none where all are the particle's, so
    // both ends compare exactly). That takes the cells inside the particles too: there p
    // and λ are jointly undetermined but for the penalties, and the cheap form of the
    // preconditioner, which does not solve J_w, needs the patch to resolve that pair (on
    // the 3D array at 7 cells per diameter, whose central cells lay more than a ring away
    // from the cut cells, 227 instead of 43 FGMRES iterations without them).
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        double fluid = 0, whole = 0;
        for (unsigned int i = 0; i < npc; ++i)
          {
            const unsigned int k = (c * npc + i) * npc + i;
            fluid += b.pressure_fluid_mass[k];
            whole += b.pressure_mass[k];
          }
        if (fluid < whole && fluid <= max_fluid_fraction * whole)
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
      for (const auto &[from, list] : Utilities::MPI::some_to_some(comm, to_owner))
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
          break;
        new_cells.clear();
        auto add_cell = [&](const unsigned int j, const int particle) {
          if (block_of(j) == Blocks::pressure && reach(cell_label[(j - o_p) / npc], particle))
            new_cells.push_back((j - o_p) / npc);
        };
        for (const unsigned int u : new_velocities)
          row_columns(u, Blocks::pressure, label[u], add_cell);
        receive(add_cell);
      }
    return label;
  }

  Epetra_Map CutCellPatch::distribute(const NewtonSystem &                 system,
                                      const std::vector<int> &             label,
                                      const std::set<std::pair<int, int>> &meeting)
  {
    const MPI_Comm     comm  = system.r_fe.get_mpi_communicator();
    const unsigned int rank  = Utilities::MPI::this_mpi_process(comm);
    const long long    first = system.blocks.range[rank][0];

    // The components: particles joined where their rings meet on any rank, each named by
    // its smallest particle (the same on every rank).
    int n_labels = 0;
    for (const int l : label)
      n_labels = std::max(n_labels, l + 1);
    n_labels = Utilities::MPI::max(n_labels, comm);
    std::vector<int> root(n_labels);
    std::iota(root.begin(), root.end(), 0);
    auto find = [&](int l) {
      while (root[l] != l)
        l = root[l] = root[root[l]];
      return l;
    };
    for (const auto &pairs : Utilities::MPI::all_gather(
           comm, std::vector<std::pair<int, int>>(meeting.begin(), meeting.end())))
      for (const auto &[a, c] : pairs)
        {
          const int ra = find(a), rc = find(c);
          root[std::max(ra, rc)] = std::min(ra, rc);
        }

    // Each component is solved by the rank that owns most of its DoFs (the first of a tie):
    // the least to send, and the particles spread over the ranks as the partition does.
    std::vector<unsigned int> owned(n_labels, 0);
    for (const int l : label)
      if (l >= 0)
        ++owned[find(l)];
    const auto                counts = Utilities::MPI::all_gather(comm, owned);
    std::vector<unsigned int> solver(n_labels, 0);
    for (int l = 0; l < n_labels; ++l)
      for (unsigned int r = 1; r < counts.size(); ++r)
        if (counts[r][l] > counts[solver[l]][l])
          solver[l] = r;

    std::vector<std::pair<long long, int>>         solved;
    std::map<unsigned int, std::vector<long long>> to_solver;
    for (unsigned int i = 0; i < label.size(); ++i)
      if (label[i] >= 0)
        {
          const int c = find(label[i]);
          if (solver[c] == rank)
            solved.emplace_back(first + i, c);
          else
            {
              to_solver[solver[c]].push_back(first + i);
              to_solver[solver[c]].push_back(c);
            }
        }
    for (const auto &[from, list] : Utilities::MPI::some_to_some(comm, to_solver))
      for (unsigned int k = 0; k < list.size(); k += 2)
        solved.emplace_back(list[k], static_cast<int>(list[k + 1]));
    std::sort(solved.begin(), solved.end());
    for (const auto &[g, c] : solved)
      {
        dofs.push_back(g);
        component.push_back(c);
      }

    IndexSet set(system.r_fe.size());
    set.add_indices(dofs.begin(), dofs.end());
    set.compress();
    const Epetra_Map map = set.make_trilinos_map(comm, true);
    Assert(map.NumMyElements() == static_cast<int>(dofs.size()), ExcInternalError());
    import     = std::make_unique<Epetra_Import>(map, system.A.trilinos_matrix().RowMap());
    residual   = std::make_unique<Epetra_Vector>(map);
    correction = std::make_unique<Epetra_Vector>(map);
    return map;
  }

  void CutCellPatch::assemble(const NewtonSystem &system, const Epetra_Map &map)
  {
    // The patch DoFs' rows of A (collective), numbered in the order of dofs, and how to
    // fetch the entries of a vector at their columns.
    const Epetra_CrsMatrix &E = system.A.trilinos_matrix();
    rows = std::make_unique<Epetra_CrsMatrix>(Copy, map, 0);
    rows->Import(E, *import, Insert);
    rows->FillComplete(E.DomainMap(), E.RangeMap());
    column_import = std::make_unique<Epetra_Import>(rows->ColMap(), E.RowMap());
    columns       = std::make_unique<Epetra_Vector>(rows->ColMap());

    // Patch number of the global DoF g, or −1.
    auto patch_index = [&](const long long g) -> int {
      const auto it = std::lower_bound(dofs.begin(), dofs.end(), g);
      return it != dofs.end() && *it == g ? it - dofs.begin() : -1;
    };
    std::vector<Eigen::Triplet<double>> entries;
    for (int r = 0; r < rows->NumMyRows(); ++r)
      {
        const int i = patch_index(rows->GRID64(r));
        Assert(i >= 0, ExcInternalError());
        for_each_entry(*rows, r, [&](const long long g, const double value) {
          const int j = patch_index(g);
          if (j >= 0 && component[j] == component[i])
            entries.emplace_back(i, j, value);
        });
      }
    const unsigned int n = dofs.size();
    matrix.resize(n, n);
    matrix.setFromTriplets(entries.begin(), entries.end());
    matrix.makeCompressed();
  }

  std::string CutCellPatch::factor(const double memory_limit)
  {
    control.resize(UMFPACK_CONTROL);
    umfpack_di_defaults(control.data());
    control[UMFPACK_IRSTEP]              = 0;
    control[UMFPACK_STRATEGY]            = UMFPACK_STRATEGY_SYMMETRIC;
    control[UMFPACK_ORDERING]            = UMFPACK_ORDERING_CHOLMOD;
    control[UMFPACK_SYM_PIVOT_TOLERANCE] = pivot_tolerance;
    control[UMFPACK_PIVOT_TOLERANCE]     = pivot_tolerance;
    std::vector<double> info(UMFPACK_INFO);
    const int           n = matrix.rows();
    auto why = [&](const int status) -> std::string {
      clear();
      return status == UMFPACK_ERROR_out_of_memory ? "UMFPACK ran out of memory" :
             status == UMFPACK_WARNING_singular_matrix ? "UMFPACK found it singular" :
                                                         "UMFPACK status " + std::to_string(status);
    };
    void *symbolic = nullptr;
    int   status   = umfpack_di_symbolic(n, n, matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                                     matrix.valuePtr(), &symbolic, control.data(), info.data());
    if (status != UMFPACK_OK)
      return why(status);
    const double estimate = bytes_per_factor_entry * info[UMFPACK_SYMMETRIC_LUNZ];
    if (memory_limit > 0 && estimate > memory_limit)
      {
        umfpack_di_free_symbolic(&symbolic);
        clear();
        std::ostringstream s;
        s << std::setprecision(2) << "its " << n << " unknowns would need about "
          << estimate / 1e9 << " GB to factor, more than the " << memory_limit / 1e9
          << " GB allowed";
        return s.str();
      }
    status = umfpack_di_numeric(matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                                matrix.valuePtr(), symbolic, &numeric, control.data(), info.data());
    umfpack_di_free_symbolic(&symbolic);
    if (status != UMFPACK_OK)
      return why(status);
    factor_memory = info[UMFPACK_PEAK_MEMORY] * info[UMFPACK_SIZE_OF_UNIT];
    return "";
  }

  void CutCellPatch::add_correction(TrilinosWrappers::MPI::Vector &      x,
                                    const TrilinosWrappers::MPI::Vector &r) const
  {
    // The transfers are collective: every rank takes part, with or without a patch.
    residual->Import(r.trilinos_vector(), *import, Insert);
    columns->Import(x.trilinos_vector(), *column_import, Insert);
    if (!dofs.empty())
      {
        // r − A x on the patch rows only (the map of the patch DoFs is in the order of
        // dofs: sorted, from an IndexSet).
        const double *xc = columns->Values();
        double *      ri = residual->Values();
        for (int i = 0; i < rows->NumMyRows(); ++i)
          {
            int     n;
            double *v;
            int *   c;
            rows->ExtractMyRowView(i, n, v, c);
            for (int k = 0; k < n; ++k)
              ri[i] -= v[k] * xc[c[k]];
          }
        const int status =
          umfpack_di_solve(UMFPACK_A, matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                           matrix.valuePtr(), correction->Values(), residual->Values(), numeric,
                           control.data(), nullptr);
        AssertThrow(status == UMFPACK_OK,
                    ExcMessage("UMFPACK failed to solve with the factored cut-cell patch "
                               "(status " + std::to_string(status) + ")."));
      }
    // Back to the owners, added: each DoF is in one rank's patch. (Epetra's Add would
    // overwrite the entries that stay on this rank.)
    x.trilinos_vector().Export(*correction, *import, Epetra_AddLocalAlso);
  }
} // namespace fdparticle
