#ifndef fdparticle_fem_velocity_operator_h
#define fdparticle_fem_velocity_operator_h

#include <deal.II/base/aligned_vector.h>
#include <deal.II/base/subscriptor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The velocity block of the Newton matrix (doc/method.md §3, §8) applied without a
   * matrix: for the Q2 velocity δu and test function v,
   *
   *   ρ c0 (δu, v) + (2μ ε(δu), ε(v)) + ρ ((w·∇)δu + (δu·∇)w, v),
   *
   * the last term (Newton's linearization of the convection at the iterate w) only for
   * Navier–Stokes. It is the same bilinear form as FluidMomentum's Jacobian, evaluated by
   * sum factorization with the Gauss rule of the cells away from the particles: MatrixFree
   * gathers and scatters each cell's values through the constraints, Q2CellKernel
   * integrates several cells at once in the lanes of the machine's vector registers. A cell cut by a particle surface has a rule of its own
   * (CutCellQuadrature), which FEEvaluation cannot take: there the operator multiplies by
   * the cell's matrix from the assembly instead (set_cut_cell_matrices). Constraints
   * (hanging nodes, periodicity, walls) act as in the assembled matrix; a constrained
   * row returns its input (the identity).
   *
   * Vectors are velocity-only, numbered by the velocity DoFHandler given to reinit(), an
   * FESystem of dim FE_Q(2) on the system's mesh.
   */
  template <int dim>
  class VelocityOperator : public Subscriptor
  {
  public:
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    /// The degree of the velocity and the Gauss points per direction of a regular cell
    /// (Introspection::velocity_degree and cell_quadrature()).
    static constexpr unsigned int degree = 2, n_points_1d = degree + 1;

    /// On the active cells, or on the cells of a multigrid level (the DoFHandler's level
    /// DoFs must be distributed; constraints then holds the level's constrained DoFs).
    void reinit(const Mapping<dim> &mapping, const DoFHandler<dim> &dof_handler,
                const AffineConstraints<double> &constraints,
                const unsigned int               level = numbers::invalid_unsigned_int);

    /// ρ, μ and the BDF weight c0 of the step; iterate: w, with the layout of
    /// initialize_dof_vector(), for the convection term (nullptr: Stokes).
    void set_coefficients(const double density, const double viscosity, const double c0,
                          const VectorType *iterate);

    /**
     * The matrices of the cut cells, indexed by the cell's active_cell_index() (an empty
     * matrix: the cell is not cut). Each is the velocity block of the cell's Jacobian in the
     * order (component c, scalar shape function a) → c n + a, n the FE_Q's shape functions:
     * what NavierStokesAssembler::assemble gives.
     */
    void set_cut_cell_matrices(std::vector<FullMatrix<double>> matrices);
    const std::vector<FullMatrix<double>> &get_cut_cell_matrices() const { return cut_matrices; }

    void initialize_dof_vector(VectorType &v) const { matrix_free.initialize_dof_vector(v); }

    /// dst = A src.
    void vmult(VectorType &dst, const VectorType &src) const;

    /// The diagonal of A (1 on constrained rows), for a Jacobi or Chebyshev smoother: each
    /// cell's diagonal, added through the constraints (exact without hanging nodes, an
    /// approximation on the masters of hanging nodes).
    void compute_diagonal(VectorType &diagonal) const;

    /// The operator as a sparse matrix on dof_handler, cell by cell through its
    /// constraints (constrained rows get AffineConstraints' diagonal): for a coarse
    /// level's algebraic solver. dof_handler is the operator's own or one of a coarser
    /// element on the same mesh (e.g. Q1), into which each cell's matrix is projected.
    void compute_matrix(const DoFHandler<dim> &          dof_handler,
                        const AffineConstraints<double> &constraints,
                        TrilinosWrappers::SparseMatrix & matrix) const;

    /// The matrix of cell batch `cell` (one cell) before the constraints, in the order of
    /// set_cut_cell_matrices(): a cut cell's own, any other's from the kernel.
    void cell_matrix(const unsigned int cell, FullMatrix<double> &matrix) const;

    /// The number of rows, and a diagonal entry (i == j) after compute_diagonal(): what
    /// deal.II's smoothers ask of a matrix.
    types::global_dof_index m() const { return matrix_free.get_vector_partitioner()->size(); }
    double                  el(const types::global_dof_index i, const types::global_dof_index j) const;
    /// The transpose product is not available (the convection term is not symmetric);
    /// multigrid's level-matrix interface declares it, and nothing here calls it.
    void Tvmult(VectorType &dst, const VectorType &src) const;

    /// The owned cells that the operator multiplies by their matrix, over all owned cells
    /// (summed over the ranks).
    double cut_cell_fraction() const;

    /// Bytes the operator holds (MatrixFree's index and mapping data, the iterate at the
    /// points, the cut cells' matrices), summed over the ranks.
    std::size_t memory_consumption() const;

    const MatrixFree<dim, double> &get_matrix_free() const { return matrix_free; }

  private:
    /// Lane l of the kernel's per-cell inputs (Q2CellKernel::apply) from cell batch cell: 1/h,
    /// the volume and, with convection, the iterate at the Gauss points.
    void load_cell_data(const unsigned int cell, const unsigned int l, double *lengths,
                        double *volumes, double *w, double *grad_w) const;

    /// out_columns = A_K in_columns for cell batch `cell`, not cut, both with rows in
    /// FEEvaluation's order of the cell's values.
    void apply_to_columns(const unsigned int cell, const FullMatrix<double> &in_columns,
                          FullMatrix<double> &out_columns) const;

    void local_apply(const MatrixFree<dim, double> &data, VectorType &dst, const VectorType &src,
                     const std::pair<unsigned int, unsigned int> &cell_range) const;

    MatrixFree<dim, double> matrix_free;
    double                  density = 1, viscosity = 1, c0 = 0;
    bool                    convection = false;
    /// w and ∇w at the quadrature points, cell batch by cell batch.
    AlignedVector<Tensor<1, dim, VectorizedArray<double>>> iterate_values;
    AlignedVector<Tensor<2, dim, VectorizedArray<double>>> iterate_gradients;
    /// See set_cut_cell_matrices(); the position in FEEvaluation's values of each row.
    std::vector<FullMatrix<double>> cut_matrices;
    std::vector<unsigned int>       matrix_row_of_evaluation_index;
    /// Per cell batch: its cell is cut (FEEvaluation's batches hold one cell here).
    std::vector<bool> batch_is_cut;
    /// Per cell: 1/h in each direction, and the volume (Q2CellKernel).
    std::vector<double> cell_inverse_lengths, cell_volumes;
    /// The diagonal of the last compute_diagonal(), for el().
    mutable VectorType diagonal_entries;
  };
} // namespace fdparticle

#endif
