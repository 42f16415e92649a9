#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/cut_cell_patch.h>

#include <Epetra_CrsMatrix.h>
#include <umfpack.h>

#include <iomanip>
#include <sstream>
#include <string>

namespace fdparticle
{
  CutCellPatch::~CutCellPatch() { clear(); }

  void CutCellPatch::clear()
  {
    patch_rows.clear();
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

    auto row_columns = [&](const unsigned int local, const auto &f) {
      int     n;
      double *v;
      int *   c;
      E.ExtractMyRowView(local, n, v, c);
      for (int k = 0; k < n; ++k)
        {
          const long long g = E.GCID64(c[k]);
          if (g >= first && g < end)
            f(static_cast<unsigned int>(g - first));
        }
    };
    for (unsigned int layer = 0;; ++layer)
      {
        // The new cells' pressure DoFs, and the velocity (and multiplier) DoFs they couple to.
        std::vector<unsigned int> new_velocities;
        for (const unsigned int c : new_cells)
          {
            cell_in[c] = true;
            for (unsigned int i = 0; i < npc; ++i)
              {
                const unsigned int p = o_p + c * npc + i;
                in_patch[p]          = true;
                row_columns(p, [&](const unsigned int j) {
                  if (block_of(j) == Blocks::velocity && !in_patch[j])
                    {
                      // The multiplier DoF at the same node and component.
                      in_patch[j]       = true;
                      in_patch[o_l + j] = true;
                      new_velocities.push_back(j);
                    }
                });
              }
          }
        if (layer == layers)
          break;
        new_cells.clear();
        for (const unsigned int u : new_velocities)
          row_columns(u, [&](const unsigned int j) {
            if (block_of(j) == Blocks::pressure && !cell_in[(j - o_p) / npc])
              {
                cell_in[(j - o_p) / npc] = true;
                new_cells.push_back((j - o_p) / npc);
              }
          });
      }

    std::vector<int> index(n_local, -1);
    for (unsigned int i = 0; i < n_local; ++i)
      if (in_patch[i])
        {
          index[i] = patch_rows.size();
          patch_rows.push_back(i);
        }
    if (patch_rows.empty())
      return "";
    std::vector<Eigen::Triplet<double>> entries;
    for (unsigned int r = 0; r < patch_rows.size(); ++r)
      {
        int     n;
        double *v;
        int *   c;
        E.ExtractMyRowView(patch_rows[r], n, v, c);
        for (int k = 0; k < n; ++k)
          {
            const long long g = E.GCID64(c[k]);
            if (g >= first && g < end && index[g - first] >= 0)
              entries.emplace_back(r, index[g - first], v[k]);
          }
      }
    matrix.resize(patch_rows.size(), patch_rows.size());
    matrix.setFromTriplets(entries.begin(), entries.end());
    matrix.makeCompressed();

    control.resize(UMFPACK_CONTROL);
    umfpack_di_defaults(control.data());
    control[UMFPACK_IRSTEP]              = 0;
    control[UMFPACK_STRATEGY]            = UMFPACK_STRATEGY_SYMMETRIC;
    control[UMFPACK_ORDERING]            = UMFPACK_ORDERING_CHOLMOD;
    control[UMFPACK_SYM_PIVOT_TOLERANCE] = pivot_tolerance;
    control[UMFPACK_PIVOT_TOLERANCE]     = pivot_tolerance;
    std::vector<double> info(UMFPACK_INFO);
    const int           n = patch_rows.size();
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
    work.resize(n);
    solution.resize(n);
    return "";
  }

  void CutCellPatch::add_correction(TrilinosWrappers::MPI::Vector &      x,
                                    const TrilinosWrappers::MPI::Vector &r) const
  {
    if (patch_rows.empty())
      return;
    const double *in  = r.trilinos_vector()[0];
    double *      out = x.trilinos_vector()[0];
    for (unsigned int i = 0; i < patch_rows.size(); ++i)
      work[i] = in[patch_rows[i]];
    const int status = umfpack_di_solve(UMFPACK_A, matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                                        matrix.valuePtr(), solution.data(), work.data(), numeric,
                                        control.data(), nullptr);
    AssertThrow(status == UMFPACK_OK, ExcMessage("UMFPACK failed to solve with the factored "
                                                 "cut-cell patch (status " +
                                                 std::to_string(status) + ")."));
    for (unsigned int i = 0; i < patch_rows.size(); ++i)
      out[patch_rows[i]] += solution[i];
  }
} // namespace fdparticle
