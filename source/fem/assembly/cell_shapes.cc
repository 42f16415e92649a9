#include <deal.II/lac/lapack_templates.h>

#include <fdparticle/fem/assembly/cell_shapes.h>

namespace fdparticle
{
  template <int dim>
  CellShapes<dim>::CellShapes(const FESystem<dim> &fe, const typename Introspection<dim>::Field field)
  {
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      {
        const unsigned int component = fe.system_to_component_index(i).first;
        if (Introspection<dim>::field(component) != field)
          continue;
        const unsigned int c = component % dim, s = fe.system_to_base_index(i).second;
        if (dofs[c].size() <= s)
          dofs[c].resize(s + 1, numbers::invalid_unsigned_int);
        dofs[c][s] = i;
      }
    n_scalar = dofs[0].size();
    for (const auto &d : dofs)
      AssertThrow(d.size() == n_scalar, ExcInternalError());
  }

  template <int dim>
  void CellShapes<dim>::reinit(const FEValues<dim> &fv)
  {
    Assert(fv.get_fe().n_dofs_per_cell() == n_scalar,
           ExcMessage("CellShapes::reinit takes the FEValues of the field's scalar element."));
    n_q = fv.n_quadrature_points;
    values.resize(n_q * n_columns());
    for (unsigned int q = 0; q < n_q; ++q)
      {
        double *r = &values[q * n_columns()];
        for (unsigned int s = 0; s < n_scalar; ++s)
          {
            r[column(0, s)] = fv.shape_value(s, q);
            const Tensor<1, dim> grad = fv.shape_grad(s, q);
            for (unsigned int d = 0; d < dim; ++d)
              r[column(1 + d, s)] = grad[d];
          }
      }
  }

  void add_gram(const unsigned int k, const unsigned int m, const double *X,
                const unsigned int ldx, double *G)
  {
    if (k == 0 || m == 0)
      return;
    // Read column-major, X is the m × k matrix Xᵀ, and Xᵀ (Xᵀ)ᵀ is syrk('n'). It updates the
    // column-major upper triangle, the row-major lower one; the other half is mirrored.
    const types::blas_int bk = k, bm = m, bldx = ldx;
    const double          one = 1.0;
    syrk("U", "N", &bm, &bk, &one, X, &bldx, &one, G, &bm);
    for (unsigned int r = 0; r < m; ++r)
      for (unsigned int c = r + 1; c < m; ++c)
        G[r * m + c] = G[c * m + r];
  }

  void add_transpose_product(const unsigned int k, const unsigned int m, const unsigned int n,
                             const double a, const double *X, const unsigned int ldx,
                             const double *Y, const unsigned int ldy, double *C,
                             const unsigned int ldc)
  {
    if (k == 0 || m == 0 || n == 0)
      return;
    // BLAS is column-major: the row-major C = Xᵀ Y is the column-major Cᵀ = Yᵀ X, i.e.
    // gemm('n', 't') on the same arrays read column-major (as deal.II's FullMatrix::Tmmult).
    const types::blas_int bk = k, bm = m, bn = n, bldx = ldx, bldy = ldy, bldc = ldc;
    const double          one = 1.0;
    gemm("n", "t", &bn, &bm, &bk, &a, Y, &bldy, X, &bldx, &one, C, &bldc);
  }

  template class CellShapes<2>;
  template class CellShapes<3>;
} // namespace fdparticle
