#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/cut_cell_patch.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Vector.h>
#include <umfpack.h>

#include <algorithm>
#include <iomanip>
#include <map>
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
    patch_rows.clear();
    ghost_rows.clear();
    ghost_import.reset();
    ghost_residual.reset();
    if (numeric != nullptr)
      umfpack_di_free_numeric(&numeric);
    factor_memory = 0;
    matrix        = Eigen::SparseMatrix<double>();
  }

  std::string CutCellPatch::initialize(const NewtonSystem &system, const unsigned int layers,
                                       const double max_fluid_fraction, const double memory_limit)
  {
    clear();
    using Blocks               = NewtonSystem::Blocks;
    const Epetra_CrsMatrix &E  = system.A.trilinos_matrix();
    const auto &            b  = system.blocks;
    const auto &            range =
      b.range[Utilities::MPI::this_mpi_process(system.r_fe.get_mpi_communicator())];
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

    std::vector<bool>         in_patch(n_local, false), cell_in(n_cells, false);
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
          new_cells.push_back(c);
      }

    // f(local column) for the columns of a local row on this rank; the others' columns of
    // block `remote_block` go to their owners (to_owner), as the patch grows across the
    // partition: a ring around another rank's cells is that rank's to add.
    const MPI_Comm comm = system.r_fe.get_mpi_communicator();
    std::map<unsigned int, std::vector<long long>> to_owner;
    auto row_columns = [&](const unsigned int local, const unsigned int remote_block,
                           const auto &f) {
      for_each_entry(E, local, [&](const long long g, double) {
        if (g >= first && g < end)
          f(static_cast<unsigned int>(g - first));
        else if (b.locate(g).first == remote_block)
          to_owner[b.owner(g)].push_back(g);
      });
    };
    // The DoFs that other ranks found for this one, as local numbers.
    auto received = [&]() {
      std::vector<unsigned int> dofs;
      for (const auto &[from, list] : Utilities::MPI::some_to_some(comm, to_owner))
        for (const long long g : list)
          dofs.push_back(g - first);
      to_owner.clear();
      return dofs;
    };
    for (unsigned int layer = 0;; ++layer)
      {
        // The new cells' pressure DoFs, and the velocity (and multiplier) DoFs they couple to.
        std::vector<unsigned int> new_velocities;
        auto add_velocity = [&](const unsigned int j) {
          if (block_of(j) == Blocks::velocity && !in_patch[j])
            {
              // The multiplier DoF at the same node and component.
              in_patch[j]       = true;
              in_patch[o_l + j] = true;
              new_velocities.push_back(j);
            }
        };
        for (const unsigned int c : new_cells)
          {
            cell_in[c] = true;
            for (unsigned int i = 0; i < npc; ++i)
              {
                const unsigned int p = o_p + c * npc + i;
                in_patch[p]          = true;
                row_columns(p, Blocks::velocity, add_velocity);
              }
          }
        for (const unsigned int j : received())
          add_velocity(j);
        if (layer == layers)
          break;
        new_cells.clear();
        auto add_cell = [&](const unsigned int j) {
          if (block_of(j) == Blocks::pressure && !cell_in[(j - o_p) / npc])
            {
              cell_in[(j - o_p) / npc] = true;
              new_cells.push_back((j - o_p) / npc);
            }
        };
        for (const unsigned int u : new_velocities)
          row_columns(u, Blocks::pressure, add_cell);
        for (const unsigned int j : received())
          add_cell(j);
      }

    for (unsigned int i = 0; i < n_local; ++i)
      if (in_patch[i])
        patch_rows.push_back(i);

    const std::unique_ptr<Epetra_CrsMatrix> ghost_matrix = import_overlap(system);
    if (patch_rows.empty())
      return "";
    assemble(system, ghost_matrix.get());
    return factor(memory_limit);
  }

  std::unique_ptr<Epetra_CrsMatrix> CutCellPatch::import_overlap(const NewtonSystem &system)
  {
    using Blocks              = NewtonSystem::Blocks;
    const Epetra_CrsMatrix &E = system.A.trilinos_matrix();
    const MPI_Comm          comm  = system.r_fe.get_mpi_communicator();
    const auto &            range = system.blocks.range[Utilities::MPI::this_mpi_process(comm)];
    const long long         first = range[0], end = range[Blocks::n_blocks];
    // The overlap: the other ranks' velocity and multiplier DoFs that the owned patch rows
    // couple to, with their rows of A (collective: every rank takes part, with or without
    // a patch). Not their pressure DoFs: a pressure row whose velocities are not all in
    // the patch would make the patch's saddle point ill-posed, so the patch takes the
    // pressure of whole cells only, as its own rings do.
    std::unique_ptr<Epetra_CrsMatrix> ghost_matrix;
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      {
        for (const unsigned int r : patch_rows)
          for_each_entry(E, r, [&](const long long g, double) {
            if ((g < first || g >= end) && system.blocks.locate(g).first != Blocks::pressure)
              ghost_rows.push_back(g);
          });
        std::sort(ghost_rows.begin(), ghost_rows.end());
        ghost_rows.erase(std::unique(ghost_rows.begin(), ghost_rows.end()), ghost_rows.end());
        IndexSet ghosts(system.r_fe.size());
        for (const long long g : ghost_rows)
          ghosts.add_index(g);
        ghosts.compress();
        const Epetra_Map ghost_map = ghosts.make_trilinos_map(comm, true);
        ghost_import   = std::make_unique<Epetra_Import>(ghost_map, E.RowMap());
        ghost_residual = std::make_unique<Epetra_Vector>(ghost_map);
        ghost_matrix   = std::make_unique<Epetra_CrsMatrix>(Copy, ghost_map, 0);
        ghost_matrix->Import(E, *ghost_import, Insert);
        ghost_matrix->FillComplete(E.DomainMap(), E.RangeMap());
        if (Utilities::MPI::sum(ghost_rows.size(), comm) == 0)
          {
            ghost_import.reset();
            ghost_residual.reset();
          }
      }
    return ghost_matrix;
  }

  void CutCellPatch::assemble(const NewtonSystem &system, const Epetra_CrsMatrix *ghost_matrix)
  {
    const Epetra_CrsMatrix &E = system.A.trilinos_matrix();
    const auto &range = system.blocks.range[Utilities::MPI::this_mpi_process(
      system.r_fe.get_mpi_communicator())];
    const long long    first = range[0], end = range[NewtonSystem::Blocks::n_blocks];
    const unsigned int n_own = patch_rows.size();
    std::vector<int>   index(end - first, -1);
    for (unsigned int r = 0; r < n_own; ++r)
      index[patch_rows[r]] = r;
    // Patch number of the global DoF g, or −1: the owned patch rows first, then the ghosts.
    auto patch_index = [&](const long long g) -> int {
      if (g >= first && g < end)
        return index[g - first];
      const auto it = std::lower_bound(ghost_rows.begin(), ghost_rows.end(), g);
      return it != ghost_rows.end() && *it == g ? n_own + (it - ghost_rows.begin()) : -1;
    };
    std::vector<Eigen::Triplet<double>> entries;
    auto add_row = [&](const Epetra_CrsMatrix &M, const int local_row, const int patch_row) {
      for_each_entry(M, local_row, [&](const long long g, const double value) {
        const int j = patch_index(g);
        if (j >= 0)
          entries.emplace_back(patch_row, j, value);
      });
    };
    for (unsigned int r = 0; r < n_own; ++r)
      add_row(E, patch_rows[r], r);
    for (unsigned int r = 0; r < ghost_rows.size(); ++r)
      add_row(*ghost_matrix, r, n_own + r); // its rows are in the order of ghost_rows
    const unsigned int n_patch = n_own + ghost_rows.size();
    matrix.resize(n_patch, n_patch);
    matrix.setFromTriplets(entries.begin(), entries.end());
    matrix.makeCompressed();

    work.resize(n_patch);
    solution.resize(n_patch);
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
    // The ghosts' residual (collective, so before any rank returns).
    if (ghost_import)
      ghost_residual->Import(r.trilinos_vector(), *ghost_import, Insert);
    if (patch_rows.empty())
      return;
    const double *in  = r.trilinos_vector()[0];
    double *      out = x.trilinos_vector()[0];
    const unsigned int n_own = patch_rows.size();
    for (unsigned int i = 0; i < n_own; ++i)
      work[i] = in[patch_rows[i]];
    for (unsigned int i = 0; i < ghost_rows.size(); ++i)
      work[n_own + i] = (*ghost_residual)[i];
    const int status = umfpack_di_solve(UMFPACK_A, matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                                        matrix.valuePtr(), solution.data(), work.data(), numeric,
                                        control.data(), nullptr);
    AssertThrow(status == UMFPACK_OK, ExcMessage("UMFPACK failed to solve with the factored "
                                                 "cut-cell patch (status " +
                                                 std::to_string(status) + ")."));
    // Restricted: only the owned entries are updated; the ghosts' belong to their ranks.
    for (unsigned int i = 0; i < n_own; ++i)
      out[patch_rows[i]] += solution[i];
  }
} // namespace fdparticle
