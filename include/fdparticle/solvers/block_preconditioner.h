#ifndef fdparticle_solvers_block_preconditioner_h
#define fdparticle_solvers_block_preconditioner_h

#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/bordered_operator.h>
#include <fdparticle/solvers/cut_cell_patch.h>
#include <fdparticle/solvers/newton_system.h>

#include <Eigen/Dense>
#include <Eigen/SparseLU>

#include <memory>
#include <vector>

class Epetra_CrsMatrix;

namespace fdparticle
{
  using namespace dealii;

  /**
   * Preconditioner of the Newton matrix for FGMRES (doc/method.md §8, iterative solve),
   * block upper triangular in the pressure p and the rest w = (u, λ, y):
   *
   *     P = [ J_w   J_wp ]      J_w: the (u, λ, y) rows and columns of the Newton matrix,
   *         [ 0     S_p  ]      solved by an inner FGMRES to inner_tolerance, or in the
   *                             cheap form (inner_solve false) one application of the
   *                             inner preconditioner below
   *
   * S_p⁻¹, the inverse of the pressure Schur complement, has two terms (Cahouet and
   * Chabard). The viscous one is cell-local: the inverse of A's own pressure block (the
   * interior-pressure penalty) minus M_p/μ, with M_p the pressure mass over the fluid part
   * of the cell plus particle_weight times the rest. In a cell inside a particle the
   * velocity is rigid, so the pressure there sees little besides its penalty; in the fluid
   * the Stokes Schur complement is close to −M_p/μ. The inertial one, −ρ_f c0 L⁻¹ with
   * L = G M_u⁻¹ Gᵀ (G = A_pu, M_u the diagonal of the velocity mass), one AMG V-cycle,
   * matters for the pressure modes of wavenumber below √(ρ_f c0/μ) (small Δt, small μ;
   * doc/scaling.md); with only a few such modes it is left out (`inertia`).
   *
   * p and λ are jointly undetermined inside a particle (only the penalties fix them), and
   * an approximation of the λ block alone spoils that balance: the inner solve of the
   * (u, λ, y) block keeps it, and so does the cut-cell patch where it reaches (the cheap
   * form relies on it). The inner preconditioner is block triangular too:
   *
   *     [ K   A_uλ ]      K = A_uu: one AMG V-cycle (ML), or the program's geometric
   *                        multigrid (NewtonSystem::Blocks::velocity_inverse)
   *     [ 0   S_λ  ]      S_λ: A_λλ + M, with the particle unknowns y, below
   *
   * Eliminating u leaves S_λλ = A_λλ + M K⁻¹ Mᵀ (M = A_λu, the pairing <η, v>_P). The
   * pairing ∫_P α λ·v + μ ∇λ:∇v is the part of K (ρ_f c0 mass + viscous term) on the
   * particle, so M K⁻¹ Mᵀ is close to M itself read as a matrix on λ (the numbering makes
   * A_λu square, NewtonSystem::Blocks): one AMG V-cycle on A_λλ + M. The particle unknowns
   * stay with λ through their Schur complement D − C S_λ⁻¹ B, kept particle by particle:
   * particle_block_size V-cycles at setup, whatever the number of particles.
   */
  class BlockPreconditioner
  {
  public:
    using BlockVector = BorderedOperator::BlockVector;

    BlockPreconditioner();
    ~BlockPreconditioner();

    /// Relative tolerance and iteration limit of the inner solve for (u, λ, y).
    double       inner_tolerance      = 1e-3;
    unsigned int max_inner_iterations = 100;
    /// false: the cheap form, one application of the inner preconditioner instead of the
    /// inner solve (IterativeSolver tries it first).
    bool inner_solve = true;
    /// Rings of cells around the cut cells in the patch solve (CutCellPatch); −1: none.
    int patch_layers = 1;
    /// Only cut cells whose fluid part is at most this fraction seed the patch.
    double patch_fluid_fraction = 0.25;
    /// A rank's patch whose factorization would need more bytes than this is dropped
    /// (0: no limit).
    double patch_memory_limit = 0;
    /// Where convection makes the patch non-symmetric, factor its symmetric part (LDLᵀ)
    /// instead of the patch (LU).
    bool symmetrize_patch = true;
    /// Whether S_p⁻¹ has its inertial term −ρ_f c0 L⁻¹: always, never, or (automatic)
    /// unless the pressure modes on which inertia outweighs viscosity (wavenumber below
    /// k* = √(ρ_f c0/μ), NewtonSystem::Blocks::slow_pressure_modes) are few and smooth
    /// on the mesh (`laplacian_needed`).
    enum class Inertia
    {
      automatic,
      always,
      never
    };
    Inertia inertia = Inertia::automatic;

    /// Build from the system's current values. The system and the operator must outlive
    /// the preconditioner's use; A keeps being read (for the current values).
    void initialize(const NewtonSystem &system, const BorderedOperator &op);
    /// Whether it is built and still fits the system's DoFs (the program's velocity block
    /// inverse is rebuilt with the mesh, and must then be initialized again).
    bool initialized() const
    {
      return multiplier_matrix != nullptr && (!velocity_inverse || velocity_inverse->initialized());
    }
    void clear();

    /// dst = P⁻¹ src, followed by the patch correction dst += R A_patch⁻¹ Rᵀ (src − J dst)
    /// (multiplicative: the patch repairs what the block triangle leaves near the cut cells).
    void vmult(BlockVector &dst, const BlockVector &src) const;

    /// Unknowns in the cut-cell patch, over all ranks.
    types::global_dof_index patch_size() const { return n_patch; }
    /// Peak memory of the patch's factorization in bytes, the largest over the ranks.
    double patch_memory() const { return patch.memory(); }
    /// Whether the patch was symmetric and factored as such.
    bool patch_symmetric() const { return patch.symmetric(); }
    /// Whether the patch was not symmetric and its symmetric part was factored.
    bool patch_symmetric_part() const { return patch.symmetric_part_factored(); }
    /// Whether S_p⁻¹ has its inertial term (L and its AMG were built).
    bool with_inertia() const { return pressure_laplacian != nullptr; }
    /// Wall time of the last initialize() and of the patch's part of it (rank 0's, s).
    double setup_time() const { return setup_seconds; }
    double patch_setup_time() const { return patch_seconds; }
    /// Wall time of the applications (vmult) since initialize(), and of the patch's part
    /// of them (its residual and solve) (rank 0's, s).
    double apply_time() const { return apply_seconds; }
    double patch_apply_time() const { return patch_apply_seconds; }

    /// Inner FGMRES iterations since initialize().
    unsigned int inner_iterations() const { return n_inner_iterations; }

    /// Where the block triangle's time goes, in the cheap form and in the inner solve
    /// alike (this rank's wall time, s, summed since initialize()): the V-cycles of the
    /// velocity and of the multiplier block, and the particle block (its border products
    /// and the solve with D − C S_λ⁻¹ B).
    struct ApplicationTimes
    {
      double velocity_cycles = 0, multiplier_cycles = 0, particle_block = 0;
    };
    const ApplicationTimes &application_times() const { return times; }

  private:
    /// Weight of the particle part of a cell in the pressure mass of S_p. The exact
    /// Schur complement of a cell almost filled by a particle is not as small as its
    /// fluid part alone says (its velocity is tied to the neighbours); 0.01 keeps the
    /// eigenvalues of S_p⁻¹ times the exact one in [0.08, 3.8] on the 2D sediment scene
    /// (0: up to 570).
    static constexpr double particle_weight = 0.01;

    /// ML settings for the two AMG preconditioners (doc/method.md §8, doc/scaling.md).
    /// Three sweeps and aggregation thresholds that drop the weak couplings of the Q2
    /// matrices (0.02 for K; 0.05 for A_λλ + M, whose rows outside the particles are only
    /// diagonal) need far fewer inner iterations than deal.II's defaults; 0.1 coarsens too
    /// fast. Large 3D problems take one sweep: a Q2 velocity row has about 375 entries, so
    /// the smoother is most of a V-cycle and saving it outweighs the extra FGMRES
    /// iterations. Smaller 3D problems and 2D keep three: there the cheap form, close to
    /// its limit, would fall back to the inner solve more often.
    static constexpr unsigned int smoother_sweeps = 3, large_3d_smoother_sweeps = 1;
    /// Unknowns of A from which a 3D problem counts as large (one sweep wins from
    /// somewhere between 27 k and 60 k).
    static constexpr types::global_dof_index large_3d_problem = 50000;
    static constexpr double       velocity_aggregation_threshold   = 0.02;
    static constexpr double       multiplier_aggregation_threshold = 0.05;
    /// ML's solver on its coarsest level (up to 2000 rows, of the multiplier block about a
    /// quarter full, where a multifrontal factorization beats KLU's; doc/history.md).
    static constexpr const char *coarse_solver = "Amesos-MUMPS";

    /// The rows of block row_block of A with the columns of the blocks col_blocks, all
    /// numbered from their block's start; entries of different column blocks at the same
    /// number are summed (used for A_λλ + A_λu, which share the numbering). The column
    /// blocks must share their numbering (u and λ do). In the multiplier numbering only
    /// the free multipliers count, numbered as owned_free_multipliers: rows and columns
    /// of the others are left out.
    std::unique_ptr<Epetra_CrsMatrix>
    extract(const unsigned int row_block, const std::vector<unsigned int> &col_blocks) const;
    /// For block numbers of the multiplier (or velocity) numbering, of any rank, their
    /// numbers in owned_free_multipliers' numbering, or −1 for a constrained multiplier.
    /// Collective.
    std::vector<int> free_multiplier_numbers(const std::vector<int> &block_numbers) const;
    /// The number of this rank's first free multiplier in owned_free_multipliers'
    /// numbering (0 if it has none).
    int first_free_multiplier() const;
    /// l_out = S_λ⁻¹ l_in by one V-cycle (nothing without free multipliers).
    void apply_multiplier_inverse() const;
    /// The free multipliers' entries of multipliers (the multiplier block of an A-layout
    /// vector) into l.
    void gather_multipliers(const double *multipliers, TrilinosWrappers::MPI::Vector &l) const;
    /// l (on the free multipliers) into multipliers (the multiplier block of an A-layout
    /// vector), at the free multipliers' places; the others are left as they are.
    void scatter_multipliers(const TrilinosWrappers::MPI::Vector &l, double *multipliers) const;

    /// The parts of initialize(), one per block, in the order they must run (the particle
    /// block uses the multiplier AMG):
    /// the AMGs of K and A_λλ + A_λu, and A_uλ and A_up (or the velocity rows that
    /// coupling_product() reads);
    void initialize_velocity_and_multiplier();
    /// the cell-local viscous term of S_p⁻¹;
    void initialize_pressure_cells();
    /// L and its AMG (Cahouet–Chabard's inertial term of S_p⁻¹; Gᵀ is A_up);
    void initialize_pressure_laplacian();
    /// the LU of the particle unknowns' Schur complement D − C S_λ⁻¹ B, particle by particle.
    void initialize_particle_block();

    /// The block-triangular preconditioner P⁻¹ alone.
    void vmult_blocks(BlockVector &dst, const BlockVector &src) const;
    /// The block-triangular approximation of J_w: dst = P_w⁻¹ src (pressure part 0).
    void vmult_rest(BlockVector &dst, const BlockVector &src) const;
    /// dst = J_w src (src's pressure part is 0; dst's is set to 0).
    void vmult_inner_operator(BlockVector &dst, const BlockVector &src) const;

    const NewtonSystem *    system = nullptr;
    const BorderedOperator *op     = nullptr;

    /// Owned DoFs of each block, numbered from the block's start.
    std::vector<IndexSet> owned;
    /// The multiplier block's unconstrained DoFs (NewtonSystem::Blocks::free_dofs), by
    /// their local number in the block, and over all ranks numbered among themselves.
    /// S_λ, its AMG and A_uλ's columns hold only these: the others are inactive
    /// multipliers, rows of A with a diagonal only and zero in a correction (most of the
    /// block; doc/scaling.md).
    std::vector<unsigned int> free_multipliers;
    IndexSet                  owned_free_multipliers;
    /// Where each block's owned entries start in the local array of an A-layout vector.
    std::vector<unsigned int> local_offset;

    /// A_uu, A_λλ + A_λu (both in the λ numbering), A_uλ and A_up, from the blocks of A;
    /// A_uu, A_uλ and A_up only where A holds the velocity block. Without it A's velocity
    /// and pressure rows hold little but A_uλ, A_up and A_pu, and coupling_product() and
    /// gradient_product() read them in place instead of copies.
    std::unique_ptr<Epetra_CrsMatrix> velocity_matrix, multiplier_matrix, coupling_matrix,
      gradient_matrix;
    /// y = A_uλ l (the velocity block's local part; l on the free multipliers) from A's
    /// velocity rows that have a multiplier entry.
    void coupling_product(const TrilinosWrappers::MPI::Vector &l, double *y) const;
    /// y = A_up p (the velocity block's local part) from A's pressure rows, as A_puᵀ p
    /// (the u–p blocks are transposes, doc/method.md §3): only A_pu's entries are read.
    void gradient_product(const double *p, double *y) const;
    /// The velocity rows of A with an entry in a multiplier column (the velocities of the
    /// particles' cells), by their local number in the velocity block.
    std::vector<unsigned int> coupled_velocity_rows;
    /// A vector in A's column layout, for coupling_product() and gradient_product().
    mutable std::unique_ptr<Epetra_Vector> column_values;
    TrilinosWrappers::PreconditionAMG velocity_amg, multiplier_amg;
    /// The program's inverse of A_uu (NewtonSystem::Blocks::velocity_inverse) in place of
    /// velocity_amg, if it gives one.
    std::shared_ptr<VelocityBlockInverse> velocity_inverse;
    /// L = G M_u⁻¹ Gᵀ (Cahouet–Chabard) and one AMG V-cycle for it.
    std::unique_ptr<Epetra_CrsMatrix> pressure_laplacian;
    TrilinosWrappers::PreconditionAMG pressure_amg;
    /// Whether `automatic` builds L: unless there are at most max_slow_pressure_modes
    /// slow modes and k* h ≤ max_slow_mode_resolution on the base mesh's cells (the
    /// shortest slow wave spans at least 2π/0.3 ≈ 20 of them). Then GMRES resolves the
    /// slow modes in about one iteration each, which costs less than L's set-up and
    /// V-cycles; on coarser cells, or with more modes, the count grows by a quarter or more
    /// (doc/scaling.md).
    bool laplacian_needed() const;
    static constexpr unsigned int max_slow_pressure_modes  = 10;
    static constexpr double       max_slow_mode_resolution = 0.3;
    /// Relative diagonal shift of L: its kernel (the pressure level) would make the
    /// coarsest AMG level singular; 1e-6 changes no other mode noticeably.
    static constexpr double laplacian_shift = 1e-6;
    /// S_p⁻¹, cell by cell (row-major blocks as NewtonSystem::Blocks::pressure_mass).
    std::vector<double> pressure_inverse;
    /// LU of D − C S_λ⁻¹ B with C S_λ⁻¹ B kept particle by particle (sparse: the
    /// particles' own blocks and D's contact blocks).
    Eigen::SparseLU<Eigen::SparseMatrix<double>> particle_schur;

    mutable unsigned int n_inner_iterations = 0;
    /// Work vectors: A layout, velocity block, free multipliers, pressure block, Krylov
    /// layout.
    mutable TrilinosWrappers::MPI::Vector full, pressure_part, u_in, u_out, l_in, l_out,
      p_in, p_out;
    mutable BlockVector                   inner_rhs;
    /// The exact solve near the cut cells, and whether any rank has one.
    CutCellPatch patch;
    bool                    patch_active = false;
    /// Whether a patch that could not be factored was reported (once per run).
    bool patch_failure_reported = false;
    types::global_dof_index n_patch      = 0;
    double                  setup_seconds = 0, patch_seconds = 0;
    mutable double          apply_seconds = 0, patch_apply_seconds = 0;
    mutable ApplicationTimes times;
  };
} // namespace fdparticle

#endif
