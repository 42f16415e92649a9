#ifndef fdparticle_solvers_newton_system_h
#define fdparticle_solvers_newton_system_h

#include <deal.II/base/index_set.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/solvers/velocity_block_inverse.h>
#include <fdparticle/solvers/velocity_block_product.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Epetra_CrsMatrix.h>

#include <array>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The Newton system of one iteration as a 2×2 block matrix (doc/method.md §8)
   *
   *     [ A  B ] [ x ]     [ r_fe ]   A: (u, λ, p) finite-element block (Trilinos, distributed)
   *     [ C  D ] [ y ] = − [ r_p  ]   y: the particle block (V_k, ω_k), m = (dim + rot)·n_free
   *
   * Particle unknown j couples only to the DoFs of the cells its ball meets, so B and C are
   * sparse: B (n × m) and Cᵀ (n × m) are distributed by rows like A, with the pattern of
   * those cells, and cost memory in proportion to the particles' cells, not m full-length
   * vectors. D (m × m) is sparse too, replicated on every rank: each free particle's
   * own block (its mass, or the kinematic closure's volume, on the diagonal) and the
   * blocks that contact forces add between two particles, so its memory grows like the
   * particles and their contacts, not like m².
   *
   * Storage only: the assembler and the particle interactions write into it, a LinearSolver
   * reads it. The blocks are public members, as the finite-element assembly writes A, B, C
   * and r_fe entry by entry through AffineConstraints.
   */
  class NewtonSystem
  {
  public:
    /// The global columns of the local row r of an Epetra graph, sorted: two graphs (or a
    /// graph and a list) compare by these, as each numbers its columns locally its own way.
    static std::vector<long long> sorted_columns(const Epetra_CrsGraph &graph, const int r);

    /// Whether A already has this sparsity pattern (same rows on every rank, same global
    /// columns in every row). Collective.
    bool has_pattern(const TrilinosWrappers::SparsityPattern &sparsity) const;

    /// The entries of A between velocity DoFs (rows and columns), over all ranks: the
    /// part of A that Blocks::velocity_product leaves out where it is set (then only the
    /// constrained rows' diagonal). Collective.
    types::global_dof_index velocity_block_nonzeros() const;

    /// Lay out the system for a step: A gets the pattern (rebuilt only if new_pattern, else
    /// zeroed), the residual the layout of the owned and relevant DoFs, B and Cᵀ the pattern
    /// border (n × m, see border_pattern), D and r_p the size m of the particle unknowns.
    void reinit(const IndexSet &locally_owned, const IndexSet &locally_relevant,
                const TrilinosWrappers::SparsityPattern &sparsity, const bool new_pattern,
                const TrilinosWrappers::SparsityPattern &border, const MPI_Comm comm);

    /// The particle unknowns as columns of B and Cᵀ (and as the particle block of a
    /// distributed vector): all m on rank 0.
    static IndexSet particle_unknowns(const unsigned int m, const MPI_Comm comm);
    /// An empty pattern for B and Cᵀ: rows the owned DoFs (writable where relevant, as cells
    /// at a partition boundary add into a neighbour's DoFs), columns the m particle unknowns.
    static TrilinosWrappers::SparsityPattern border_pattern(const IndexSet &locally_owned,
                                                            const IndexSet &locally_relevant,
                                                            const unsigned int m,
                                                            const MPI_Comm     comm);

    /// Number m of particle unknowns.
    unsigned int n_particle_unknowns() const { return D.rows(); }
    /// x += B y on the owned DoFs.
    void add_border(const Eigen::VectorXd &y, TrilinosWrappers::MPI::Vector &x) const;
    /// C x, summed over the ranks. Collective.
    Eigen::VectorXd border_product(const TrilinosWrappers::MPI::Vector &x) const;
    /// Compress B and Cᵀ after their entries are written (op: add or insert) and note
    /// which owned rows hold any, the few rows the products below walk. Collective.
    void compress_border(const VectorOperation::values op);
    /// f(local row, column, value) for each non-zero owned entry of B or Cᵀ (border is one
    /// of the two), over the rows compress_border noted; local rows are in the order of
    /// r_fe's owned entries.
    template <typename F>
    void for_each_border_entry(const TrilinosWrappers::SparseMatrix &border, const F &f) const;

    /// Zero the residuals, and A, B, C, D too if with_matrix.
    void zero(const bool with_matrix);

    /// 2-norm of the residual (r_fe; r_p).
    double residual_norm() const;

    /// What an iterative solver needs beyond the matrix, set by the program when the
    /// unknowns change (set_blocks) and each step (the scales). A direct solver ignores it.
    struct Blocks
    {
      /// The blocks in the order each rank numbers them (Introspection's order of fields).
      enum Block : unsigned int
      {
        velocity,
        multiplier,
        pressure,
        n_blocks
      };

      /// Each rank owns one contiguous range of DoFs and numbers it block by block,
      /// u | λ | p: rank r's DoFs of block b are [range[r][b], range[r][b + 1]). Counted
      /// over the ranks in order, block b's DoFs have a numbering of their own (the
      /// "block numbering", 0 … size(b) − 1). Each rank's velocity DoF i and multiplier DoF
      /// i sit at the same node and component, so the λ–u block of A is square in the
      /// block numbering (doc/method.md §8).
      std::vector<std::array<types::global_dof_index, n_blocks + 1>> range;
      /// offset[r][b]: block number of rank r's first DoF of block b.
      std::vector<std::array<types::global_dof_index, n_blocks>> offset;

      /// The rank that owns the global DoF g.
      unsigned int owner(const types::global_dof_index g) const;
      /// Block and block number of the global DoF g.
      std::pair<unsigned int, types::global_dof_index> locate(const types::global_dof_index g) const;
      /// The DoFs of block b over all ranks.
      types::global_dof_index size(const unsigned int b) const;
      /// The global DoF numbers of block b (one interval per rank).
      IndexSet global_dofs(const unsigned int b) const;
      /// For each velocity component, which owned velocity DoFs (in order) belong to it:
      /// the near null space of AMG on the velocity and multiplier blocks.
      std::vector<std::vector<bool>> velocity_modes;
      /// The pressure mass matrix of each owned cell, and over its fluid part only (the
      /// quadrature points of no particle): the pressure DoFs of a cell are consecutive,
      /// so block k (pressure_dofs_per_cell² entries, row-major) belongs to the owned
      /// pressure DoFs k·n … (k+1)·n − 1 in local order. Written by the assembler with
      /// the Jacobian when pressure_dofs_per_cell > 0 (the iterative solver only).
      std::vector<double> pressure_mass, pressure_fluid_mass;
      unsigned int        pressure_dofs_per_cell = 0;
      /// For each owned cell (in the order of its pressure DoFs), the particle that
      /// covers most of its quadrature points, or −1: which particle's cut-cell patch a
      /// cell seeds. Written with the pressure masses.
      std::vector<int> cell_particle;
      /// For each owned cell (the same order), its fluid fraction 1 − θ_K (doc/method.md
      /// §7): 1 for a fluid cell, 0 inside a particle. Written with the pressure masses.
      std::vector<double> cell_fluid_fraction;
      /// The diagonal of the velocity mass matrix (0 at constrained DoFs), in r_fe's
      /// layout, written with the pressure masses.
      TrilinosWrappers::MPI::Vector velocity_mass;
      /// The owned DoFs (local numbers, ascending) that no constraint of the Newton
      /// correction fixes: the unknowns of the Krylov vectors (FreeUnknowns). Written with
      /// A's pattern each step.
      std::vector<unsigned int> free_dofs;
      /// The unknowns of one free particle (its velocity and rotations), consecutive in
      /// the particle block: the size of the diagonal blocks of D.
      unsigned int particle_block_size = 0;
      /// ρ_f c0 and μ of the step: the scales of the pressure Schur complement.
      double mass_coefficient = 0, viscosity = 0;
      /// k* = √(ρ_f c0/μ): below this wavenumber the fluid's inertia outweighs its
      /// viscosity on a pressure mode (doc/method.md §8).
      double inertial_wavenumber() const { return std::sqrt(mass_coefficient / viscosity); }
      /// The box's pressure modes below inertial_wavenumber() (Box::count_modes_below),
      /// counted up to max_counted_pressure_modes.
      unsigned int slow_pressure_modes = 0;
      static constexpr unsigned int max_counted_pressure_modes = 100;
      /// The edge of the base mesh's cells (Domain::base_cell_size), the mesh's largest.
      double base_cell_size = 0;
      /// The velocity block's inverse by the program's geometric multigrid, or nullptr:
      /// the preconditioner builds an AMG V-cycle on A_uu itself.
      std::shared_ptr<VelocityBlockInverse> velocity_inverse;
      /// The velocity block applied without a matrix where A leaves it out, or nullptr.
      std::shared_ptr<VelocityBlockProduct> velocity_product;
    };
    Blocks blocks;

    TrilinosWrappers::SparseMatrix A;
    /// B and C transposed; empty (0 × 0) when there are no particle unknowns.
    TrilinosWrappers::SparseMatrix B, C_transposed;
    Eigen::SparseMatrix<double>    D;
    TrilinosWrappers::MPI::Vector  r_fe;
    Eigen::VectorXd                r_p;

  private:
    /// The owned rows (local numbers, ascending) where B or Cᵀ hold entries: those of the
    /// particles' cells, a small part of all rows.
    std::vector<int> border_rows;
  };


  template <typename F>
  void NewtonSystem::for_each_border_entry(const TrilinosWrappers::SparseMatrix &border,
                                           const F &                             f) const
  {
    Assert(&border == &B || &border == &C_transposed,
           ExcMessage("for_each_border_entry walks B or C_transposed only."));
    if (border.m() == 0)
      return;
    const Epetra_CrsMatrix &E = border.trilinos_matrix();
    for (const int r : border_rows)
      {
        int     length;
        double *values;
        int *   local_columns;
        E.ExtractMyRowView(r, length, values, local_columns);
        for (int k = 0; k < length; ++k)
          if (values[k] != 0)
            f(r, static_cast<unsigned int>(E.GCID(local_columns[k])), values[k]);
      }
  }
} // namespace fdparticle

#endif
