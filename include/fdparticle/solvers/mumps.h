#ifndef fdparticle_solvers_mumps_h
#define fdparticle_solvers_mumps_h

#include <mpi.h>

#include <vector>

class Epetra_CrsMatrix;

namespace fdparticle
{
  /**
   * What the two users of MUMPS (through Amesos) share: the direct solver of the whole
   * system (DirectSolver) and the iterative solver's cut-cell patch (CutCellPatch).
   */
  namespace mumps
  {
    /**
     * Nested-dissection ordering of the symmetrized pattern of E, computed by METIS on
     * rank 0 after gathering the pattern there (MUMPS analyses on the host anyway; Debian's
     * MUMPS has neither METIS nor SCOTCH of its own, and its PORD needs more flops and a
     * slower analysis, doc/performance.md). E's rows
     * must be numbered 0 … n − 1 over all ranks. Returns MUMPS's PERM_IN on rank 0 (1-based
     * position of each unknown in the pivot order), an empty vector elsewhere. Collective.
     */
    std::vector<int> nested_dissection(const Epetra_CrsMatrix &E, const MPI_Comm comm);

    /// INFOG(1) for a numerically singular matrix, and for an allocation that failed
    /// (INFOG(2) then says what it asked for, in entries of its real arrays).
    constexpr int singular = -10, out_of_memory = -13;

    /// Whether INFOG(1) says that the working space estimated by the analysis was short
    /// (−8, −9, −14, −15, −17): then analyse again with more (ICNTL(14)).
    bool short_of_workspace(const int infog_1);

    /// MUMPS reports large counts as −(count in millions).
    inline double count(const int v) { return v >= 0 ? double(v) : -1e6 * v; }

    /// ICNTL(14): extra working space in percent of the analysis' estimate. MUMPS's default
    /// is 20; the saddle-point matrices here delay pivots (doc/performance.md, working
    /// space), so the margin starts higher. Each retry after a shortfall analyses again
    /// with workspace_growth times the margin, at most max_workspace_retries times
    /// (30 % → 1920 %): a shortfall beyond that is no longer an estimate that was short but
    /// a matrix MUMPS cannot factor.
    constexpr int initial_workspace_percent = 30;
    constexpr int workspace_growth          = 4;
    constexpr int max_workspace_retries     = 3;
  } // namespace mumps
} // namespace fdparticle

#endif
