#ifndef fdparticle_solvers_cut_cell_patch_h
#define fdparticle_solvers_cut_cell_patch_h

#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/mumps.h>
#include <fdparticle/solvers/newton_system.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

class Epetra_CrsMatrix;
class Epetra_Import;
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
   * particle surfaces: with particle-following refinement the interior is coarse.
   *
   * The rings grow across the partition (each rank hands the others the DoFs of theirs
   * that its cells reach), each DoF carrying the particle whose seed cells reached it;
   * particles whose rings meet form one component, and entries of A between two
   * components are left out: the patch matrix is block diagonal, one block per component,
   * whatever the partition. All ranks factor it together (MUMPS, each rank's rows where
   * A has them): the patch's rows of A and its residual stay on their owners, and a
   * large particle's patch is shared by the ranks instead of held up by one. With its
   * multiplier rows negated the patch matrix is symmetric wherever the Jacobian has no
   * convection (Stokes, a fluid at rest), and is then factored as LDLᵀ: half the
   * factors of LU, in about the same time. Where convection makes it non-symmetric, its
   * symmetric part is factored so (or the patch itself as LU, `symmetric_part` false):
   * the correction's residual stays exact, only its local solve leaves out the
   * antisymmetric part of the convection. The patch is solved whole: solved
   * approximately per rank where the partition cuts it, FGMRES stalled on 2 ranks at
   * 1 M unknowns (doc/scaling.md). With one ring the FGMRES count stops growing with
   * refinement, and the cheap form of the preconditioner (no inner solve) converges on
   * 3D scenes.
   */
  class CutCellPatch
  {
  public:
    CutCellPatch();
    ~CutCellPatch();
    CutCellPatch(const CutCellPatch &) = delete;
    CutCellPatch &operator=(const CutCellPatch &) = delete;

    /// Collect the patch of the current system and factor it: the cut cells whose fluid
    /// part is at most max_fluid_fraction of the cell, and `layers` rings of cells
    /// beyond them; a patch that is not symmetric is factored by its symmetric part if
    /// symmetric_part, else as LU. A patch whose factorization would need more than
    /// memory_limit bytes on one rank (by MUMPS's analysis; 0: no limit) is not factored.
    /// Returns why the patch was not factored (it is then empty), the same on every rank,
    /// or an empty string. Collective.
    std::string initialize(const NewtonSystem &system, const unsigned int layers,
                           const double max_fluid_fraction, const double memory_limit,
                           const bool symmetric_part);
    void clear();

    /// x += R_patchᵀ A_patch⁻¹ R_patch (r − A x), in A's layout, where r is the
    /// right-hand side less the other terms of these rows (the particle border B y). The
    /// residual is formed on the patch rows only, not a product with all of A.
    /// Collective (x at the patch rows' columns on other ranks, and MUMPS's solve).
    void add_correction(TrilinosWrappers::MPI::Vector &x, const TrilinosWrappers::MPI::Vector &r) const;

    /// DoFs of the patch among this rank's.
    unsigned int size() const { return dofs.size(); }
    /// Whether the patch matrix was symmetric and factored as such (LDLᵀ).
    bool symmetric() const { return is_symmetric; }
    /// Whether the patch matrix was not symmetric and its symmetric part was factored.
    bool symmetric_part_factored() const { return factored_symmetric_part; }
    /// Memory that MUMPS allocated for the factorization on the rank that needed most, in
    /// bytes (INFOG(18)); the same on every rank.
    double memory() const { return factor_memory; }

  private:
    /// The patch DoFs among this rank's (local numbers, −1: not in the patch), each
    /// labelled with the particle whose seed cells reached it, and the pairs of particles
    /// whose rings meet (smaller first); where A leaves out the velocity block, row_cells
    /// marks this rank's cells (in the order of their pressure DoFs) that add to the
    /// patch's velocity rows. Collective.
    std::vector<int> grow(const NewtonSystem &system, const unsigned int layers,
                          const double max_fluid_fraction,
                          std::set<std::pair<int, int>> &meeting,
                          std::vector<bool> &            row_cells) const;
    /// From the labels of grow: this rank's patch DoFs (dofs) and the component of each
    /// (its smallest particle). Collective.
    void find_components(const NewtonSystem &system, const std::vector<int> &label,
                         const std::set<std::pair<int, int>> &meeting);
    /// The patch DoFs' rows of A (with the velocity block of row_cells where A leaves it
    /// out), and the patch matrix from them, its rows and columns numbered 0 … n − 1 over
    /// all ranks in the order of the DoFs. Collective.
    void assemble(const NewtonSystem &system, const std::vector<bool> &row_cells);
    /// Factor the patch matrix unless it would need more than memory_limit bytes on one
    /// rank (0: no limit), and release it; returns why not, or an empty string. Collective.
    std::string factor(const double memory_limit, const bool symmetric_part,
                       const MPI_Comm comm);
    /// Whether the patch matrix is symmetric, by x·My = y·Mx for two vectors fixed by the
    /// patch numbering (the same answer on any number of ranks) to 10⁻¹² of the scale of
    /// their terms. Collective.
    bool test_symmetry() const;

    /// This rank's patch DoFs (local rows of A, ascending) and the component of each.
    std::vector<int> dofs;
    std::vector<int> component;
    /// The patch's multiplier rows, which the patch matrix and its right-hand side take
    /// with the opposite sign: (F1) tests λ with −<λ, v>, (F3) u with +<η, u> (doc/method.md
    /// §0), so with these rows negated the patch matrix is symmetric wherever A's velocity
    /// block is (no convection in the Jacobian), and MUMPS factors it as such.
    std::vector<bool> negated;
    bool              is_symmetric = false, factored_symmetric_part = false;
    /// For each of this rank's patch DoFs, the patch number of the DoF it is ordered with
    /// (mumps::nested_dissection): a multiplier DoF with the velocity DoF at its node and
    /// component, the others with themselves. Kept until ordered.
    std::vector<int> group;
    /// The patch DoFs' rows of A (all their columns), for the residual on the patch, and
    /// how to fetch x at their columns.
    std::unique_ptr<Epetra_CrsMatrix> rows;
    std::unique_ptr<Epetra_Import>    column_import;
    std::unique_ptr<Epetra_Vector>    columns;
    /// The patch matrix until it is factored, and MUMPS's factorization of it, ordered by
    /// METIS (mumps::nested_dissection). MUMPS's default threshold pivoting (CNTL(1) =
    /// 0.01) is kept: it solves the patch to a relative residual of about 10⁻⁹, a smaller
    /// threshold (10⁻⁸) leaves 10⁻⁵ for little saved time.
    std::unique_ptr<Epetra_CrsMatrix>     matrix;
    std::unique_ptr<mumps::Factorization> factorization;
    double                                factor_memory = 0;
    /// The patch rows of each rank (counts and offsets in the patch numbering, on rank
    /// 0), to gather the residual and scatter the correction, and the whole right-hand
    /// side of a solve, on rank 0.
    std::vector<int>            rank_rows, rank_offsets;
    mutable std::vector<double> patch_rhs, local_residual;
  };
} // namespace fdparticle

#endif
