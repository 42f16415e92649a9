#ifndef fdparticle_solvers_cut_cell_patch_h
#define fdparticle_solvers_cut_cell_patch_h

#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/newton_system.h>

#include <Eigen/Sparse>

#include <memory>
#include <set>
#include <string>
#include <vector>

class Epetra_CrsMatrix;
class Epetra_Import;
class Epetra_Map;
class Epetra_Vector;

namespace fdparticle
{
  using namespace dealii;

  /**
   * An exact solve of the (u, λ, p) block A restricted to the DoFs around the cut cells
   * of the particles, for the iterative solver's preconditioner (doc/method.md §8). The
   * cell-local pressure approximation cannot fit a cell that a particle almost covers:
   * some of its pressure modes are nearly free (the rigid velocity has no divergence to
   * test), others stiff (its velocity nodes are shared with fluid cells), and which is
   * which depends on the neighbours (doc/scaling.md). The patch holds the pressure of
   * the cut cells that a particle almost covers and of the cells inside the particles
   * (where p and λ are jointly undetermined but for the penalties), the velocity and
   * multiplier DoFs of those cells, and `layers` more rings of cells grown through the
   * matrix graph; everything outside is held fixed. Most of it is the shell around the
   * particle surfaces: with particle-following refinement the interior is coarse (2 642
   * of 58 838 patch unknowns on the 3D array at c = 0.125 and 10 cells per diameter).
   *
   * The rings grow across the partition (each rank hands the others the DoFs of theirs
   * that its cells reach), each DoF carrying the particle whose seed cells reached it;
   * particles whose rings meet form one component. Each component is solved whole by
   * one rank, the one that owns most of its DoFs: it fetches their rows of A once per
   * factorization and their residual once per application, and sends the correction
   * back to the owners. So the patch and its solve do not depend on the partition. Where
   * the partition ran through the patch and each rank solved its part (with one layer of
   * overlap), the sediment step at n = 21 (1 M unknowns) stalled on 2 ranks (153 FGMRES
   * iterations, 74 on one rank; doc/scaling.md, Across ranks). Entries of A between two
   * components are left out, as on one rank: the components are independent blocks.
   * With one ring the FGMRES count stops growing with refinement, and the cheap form of
   * the preconditioner (no inner solve) converges on 3D scenes (doc/scaling.md).
   */
  class CutCellPatch
  {
  public:
    CutCellPatch() = default;
    ~CutCellPatch();
    CutCellPatch(const CutCellPatch &) = delete;
    CutCellPatch &operator=(const CutCellPatch &) = delete;

    /// Collect the patch of the current system and factor it: the cut cells whose fluid
    /// part is at most max_fluid_fraction of the cell, and `layers` rings of cells
    /// beyond them. A patch whose factorization would need more than memory_limit bytes
    /// (estimated from UMFPACK's symbolic analysis; 0: no limit) is not factored.
    /// Returns why the patch was not factored (it is then empty), or an empty string.
    /// Collective.
    std::string initialize(const NewtonSystem &system, const unsigned int layers,
                           const double max_fluid_fraction, const double memory_limit);
    void clear();

    /// x += R_patchᵀ A_patch⁻¹ R_patch (r − A x), in A's layout, where r is the
    /// right-hand side less the other terms of these rows (the particle border B y). The
    /// residual is formed on the patch rows only, not a product with all of A.
    /// Collective (the residual, x at the patch rows' columns and the correction travel
    /// between the owners and the solving ranks).
    void add_correction(TrilinosWrappers::MPI::Vector &x, const TrilinosWrappers::MPI::Vector &r) const;

    /// DoFs of the patch that this rank solves.
    unsigned int size() const { return dofs.size(); }
    /// Peak memory of this rank's factorization in bytes, as UMFPACK measured it.
    double memory() const { return factor_memory; }

  private:
    /// The patch DoFs among this rank's (local numbers, −1: not in the patch), each
    /// labelled with the particle whose seed cells reached it, and the pairs of particles
    /// whose rings meet (smaller first). Collective.
    std::vector<int> grow(const NewtonSystem &system, const unsigned int layers,
                          const double max_fluid_fraction,
                          std::set<std::pair<int, int>> &meeting) const;
    /// From the labels of grow: the DoFs this rank solves (dofs, component), fetched
    /// from the ranks that own them (import); returns their map. Collective.
    Epetra_Map distribute(const NewtonSystem &system, const std::vector<int> &label,
                    const std::set<std::pair<int, int>> &meeting);
    /// Fetch the rows of A of the DoFs in map (those of distribute), and the patch matrix
    /// from them. Collective.
    void assemble(const NewtonSystem &system, const Epetra_Map &map);
    /// Factor the patch matrix unless it would need more than memory_limit bytes (0: no
    /// limit); returns why not, or an empty string.
    std::string factor(const double memory_limit);

    /// UMFPACK takes a diagonal pivot unless it is below this fraction of its column. The
    /// patch is a saddle point: the multiplier rows inside a particle and the pressure rows
    /// of fluid cells have (almost) nothing on the diagonal until the velocities they
    /// couple to are eliminated. With UMFPACK's default tolerance (10⁻³), in its
    /// automatic choice of the unsymmetric strategy and in the symmetric one, it rejected
    /// so many diagonal pivots that the fill outgrew its memory on the 3D array at
    /// c = 0.125 and 10 cells per diameter (58 838 patch unknowns); with 10⁻⁸ it took
    /// 3 554 off-diagonal pivots and 1.6 GB (measured on 2026-11-25). Inside a
    /// preconditioner the lost accuracy is the outer FGMRES's to correct.
    static constexpr double pivot_tolerance = 1e-8;
    /// Peak memory of the factorization per entry of L + U, for the estimate from
    /// UMFPACK's symbolic analysis (the entries with diagonal pivots, before anything is
    /// factored): 14–17 bytes on the patches of the 3D sediment and array scenes
    /// (4 630–25 830 unknowns, measured on 2026-11-25). The off-diagonal pivots added up
    /// to 45 % more entries there. UMFPACK's own estimate, an upper bound, was 2.8–3.2
    /// times the peak.
    static constexpr double bytes_per_factor_entry = 16;

    /// The global DoFs whose patch this rank solves (sorted; the patch order) and the
    /// component of each (its smallest particle); how to fetch their residual from the
    /// owners and send the correction back, and the two vectors.
    std::vector<long long>         dofs;
    std::vector<int>               component;
    std::unique_ptr<Epetra_Import> import;
    std::unique_ptr<Epetra_Vector> residual, correction;
    /// The patch DoFs' rows of A (all their columns), for the residual on the patch, and
    /// how to fetch x at their columns.
    std::unique_ptr<Epetra_CrsMatrix> rows;
    std::unique_ptr<Epetra_Import>    column_import;
    std::unique_ptr<Epetra_Vector>    columns;
    /// UMFPACK's LU of the patch matrix (its C interface: the symbolic analysis gives the
    /// memory estimate that decides, before the numeric factorization, whether the patch
    /// is affordable). Without iterative refinement: the patch solve is
    /// one correction inside a preconditioner, and the two refinement steps UMFPACK does by
    /// default tripled its cost (each a residual and a further forward/backward solve).
    /// Ordered by CHOLMOD (the better of AMD and METIS's nested dissection): on the shell
    /// of the 3D sediment step at 116 k unknowns (10 846 in the patch) METIS won and the
    /// whole run needed 0.76 times the memory of AMD alone (measured on 2026-11-25).
    /// The symmetric strategy (the ordering of A + Aᵀ, diagonal pivots preferred): the
    /// patch matrix is structurally symmetric. See pivot_tolerance for the pivots.
    /// The patch matrix (compressed columns, as UMFPACK reads it) stays: the solve reads it.
    Eigen::SparseMatrix<double> matrix;
    std::vector<double>         control;
    void *                      numeric       = nullptr;
    double                      factor_memory = 0;
  };
} // namespace fdparticle

#endif
