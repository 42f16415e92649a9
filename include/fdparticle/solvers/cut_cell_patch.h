#ifndef fdparticle_solvers_cut_cell_patch_h
#define fdparticle_solvers_cut_cell_patch_h

#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <fdparticle/solvers/newton_system.h>

#include <vector>

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
   * the cut cells that a particle almost covers, the velocity and multiplier DoFs of
   * those cells, and `layers` more rings of cells grown through the matrix graph;
   * everything outside is held fixed.
   *
   * Each rank takes only its own DoFs (a restricted additive Schwarz across the ranks):
   * its patch matrix is local and factored by UMFPACK, so nothing is communicated.
   * With one ring the FGMRES count stops growing with refinement, but on meshes of up to
   * 200 k unknowns the patch holds a quarter to a half of them (doc/scaling.md): the
   * preconditioner uses it only if asked to (Solver/Cut cell patch layers).
   */
  class CutCellPatch
  {
  public:
    /// Collect the patch of the current system and factor it: the cut cells whose fluid
    /// part is at most max_fluid_fraction of the cell, and `layers` rings of cells
    /// beyond them.
    void initialize(const NewtonSystem &system, const unsigned int layers,
                    const double max_fluid_fraction);
    void clear();

    /// x += R_patchᵀ A_patch⁻¹ R_patch r on the owned entries (A's layout).
    void add_correction(TrilinosWrappers::MPI::Vector &x, const TrilinosWrappers::MPI::Vector &r) const;

    /// DoFs in this rank's patch.
    unsigned int size() const { return patch_rows.size(); }

  private:
    /// Local rows of A in the patch, in patch order.
    std::vector<unsigned int> patch_rows;
    SparsityPattern          pattern;
    SparseMatrix<double>     matrix;
    SparseDirectUMFPACK      factorization;
    mutable Vector<double>   work;
  };
} // namespace fdparticle

#endif
