#ifndef fdparticle_solvers_mumps_h
#define fdparticle_solvers_mumps_h

#include <mpi.h>

#include <memory>
#include <vector>

class Epetra_CrsMatrix;

namespace fdparticle
{
  /**
   * What the two users of MUMPS share: the direct solver of the whole system
   * (DirectSolver, through Amesos) and the iterative solver's cut-cell patch
   * (CutCellPatch, through Factorization below).
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
     *
     * `group` (one entry per local row of E, or empty) names for each row the row it is
     * ordered with: METIS orders the graph of the groups, and the rows of a group follow
     * each other in the order of their numbers. Rows that couple to nearly the same rows
     * (a velocity and the multiplier at its node) so form a smaller graph for METIS.
     */
    std::vector<int> nested_dissection(const Epetra_CrsMatrix &E, const MPI_Comm comm,
                                       const std::vector<int> &group = {});

    /// INFOG(1) for a numerically singular matrix, and for an allocation that failed
    /// (INFOG(2) then says what it asked for, in entries of its real arrays).
    constexpr int singular = -10, out_of_memory = -13;

    /// Whether INFOG(1) says that the working space estimated by the analysis was short
    /// (−8, −9, −14, −15, −17): then analyse again with more (ICNTL(14)).
    bool short_of_workspace(const int infog_1);

    /**
     * MUMPS's factorization through its C interface, of an n × n matrix whose entries
     * the ranks of a communicator hold in parts (MUMPS's distributed assembled input), for
     * one right-hand side at a time gathered on rank 0: LU, or for a symmetric matrix
     * LDLᵀ with 1 × 1 and 2 × 2 pivots (MUMPS's SYM = 2, which allows an indefinite
     * matrix and zeros on the diagonal), which holds about half the factors. Unlike
     * Amesos it keeps no copy of the matrix once factored.
     */
    class Factorization
    {
    public:
      /// The n × n matrix of which this rank holds the entries (rows[k], columns[k],
      /// values[k]), numbered 0 … n − 1; they are kept until factored. A symmetric
      /// matrix is given by its entries with rows[k] ≥ columns[k] only. Entries given
      /// at the same place are summed (MUMPS's assembled input). Collective.
      Factorization(const MPI_Comm comm, const int n, const bool symmetric,
                    std::vector<int> rows, std::vector<int> columns,
                    std::vector<double> values);
      ~Factorization();
      Factorization(const Factorization &) = delete;
      Factorization &operator=(const Factorization &) = delete;

      /// Analyse the matrix with the pivot order `ordering` (PERM_IN, on rank 0; empty:
      /// MUMPS's own) and workspace_percent for ICNTL(14); again after a factorization
      /// that was short of workspace. Returns INFOG(1). Collective.
      int analyse(std::vector<int> &ordering, const int workspace_percent);
      /// The analysis' estimate of the factorization's memory on the rank that needs most,
      /// in bytes (INFOG(16)); the same on every rank.
      double estimated_memory() const;
      /// Factor the analysed matrix; once it succeeds, release the entries. Returns
      /// INFOG(1). Collective.
      int factor();
      /// Memory of the factorization on the rank that needed most, in bytes (INFOG(18)).
      double memory() const;
      /// Overwrite b (the whole right-hand side on rank 0, ignored elsewhere) with the
      /// solution. Returns INFOG(1). Collective.
      int solve(std::vector<double> &b);

    private:
      /// MUMPS's instance (its C structure) and the entries it reads until factored.
      struct Instance;
      std::unique_ptr<Instance> instance;
    };

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
