#ifndef fdparticle_fem_assembly_cell_shapes_h
#define fdparticle_fem_assembly_cell_shapes_h

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>

#include <fdparticle/fem/introspection.h>

#include <array>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The scalar shape functions of one vector field (u or λ) at all quadrature points of a
   * cell, as one row-major matrix: row q holds the values of the n scalar functions, then
   * their derivatives ∂_0, …, ∂_{dim−1} (the "features" 0, 1, …, dim). Every component of
   * the field uses the same scalar functions, so a Jacobian block between two components
   * is a contraction over the points, Σ_q w_q X(q, s) Y(q, t): one matrix product for the
   * whole cell (add_transpose_product) instead of a double loop over 166 shape functions at
   * each of the thousands of points of a 3D level-set rule (doc/method.md §7).
   */
  template <int dim>
  class CellShapes
  {
  public:
    CellShapes(const FESystem<dim> &fe, const typename Introspection<dim>::Field field);

    /// Read the scalar shape functions at the points of fv, a FEValues of the field's
    /// scalar element (not of the FESystem).
    void reinit(const FEValues<dim> &fv);

    unsigned int n_points() const { return n_q; }
    /// Scalar functions per component (27 for Q2 in 3D).
    unsigned int n_functions() const { return n_scalar; }
    /// Columns of a row: (dim + 1) features × n_functions().
    unsigned int n_columns() const { return (dim + 1) * n_scalar; }
    /// Column of scalar function s in feature f (0: value, 1 + d: ∂_d).
    unsigned int column(const unsigned int f, const unsigned int s) const { return f * n_scalar + s; }
    const double *row(const unsigned int q) const { return &values[q * n_columns()]; }
    const double *data() const { return values.data(); }
    /// The cell's local DoF of vector component c (0..dim−1) and scalar function s.
    unsigned int dof(const unsigned int c, const unsigned int s) const { return dofs[c][s]; }

  private:
    unsigned int                                n_scalar = 0, n_q = 0;
    std::array<std::vector<unsigned int>, dim> dofs;
    std::vector<double>                         values;
  };

  /**
   * C += a Xᵀ Y for row-major X (k × m, leading dimension ldx), Y (k × n, ldy) and C (m × n,
   * ldc), by BLAS: the contraction over quadrature points behind the cell products.
   */
  /**
   * G += Xᵀ X for row-major X (k × m, leading dimension ldx) and G (m × m): the Gram matrix
   * of the columns of X, symmetric, by BLAS's rank-k update (half the work of a product).
   * Rows scaled by √w give Σ_q w_q x(q) x(q)ᵀ, for weights w ≥ 0.
   */
  void add_gram(const unsigned int k, const unsigned int m, const double *X,
                const unsigned int ldx, double *G);

  void add_transpose_product(const unsigned int k, const unsigned int m, const unsigned int n,
                             const double a, const double *X, const unsigned int ldx,
                             const double *Y, const unsigned int ldy, double *C,
                             const unsigned int ldc);
} // namespace fdparticle

#endif
