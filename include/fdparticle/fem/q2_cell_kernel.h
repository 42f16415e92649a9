#ifndef fdparticle_fem_q2_cell_kernel_h
#define fdparticle_fem_q2_cell_kernel_h

namespace fdparticle
{
  /**
   * The cell operator of VelocityOperator on `lanes` axis-aligned cells at once, by sum
   * factorization with the 3-point Gauss rule (doc/method.md §8): for the Q2 velocity
   * values u of each cell (lexicographic, component by component),
   *
   *   out = ∫ ρ c0 u·v + ρ ((w·∇)u + (u·∇)w)·v + μ (∇u + ∇uᵀ):∇v
   *
   * over the cell, for every test function v, the convection term only if w is given. The
   * cells run in the lanes of the machine's vector registers: this file is compiled for the
   * build machine's instruction set, where the deal.II library's own kernels run one cell
   * at a time. It knows no deal.II type; arrays are lane-interleaved, entry [k][lane].
   */
  template <int dim>
  struct Q2CellKernel
  {
    /// Cells handled at once (one AVX-512 register of doubles; narrower machines split it).
    static constexpr unsigned int lanes = 8;
    static constexpr unsigned int n_1d = 3, n_dofs = dim == 2 ? 9 : 27, n_points = n_dofs;

    /**
     * in, out: [dim × n_dofs][lanes]; inverse_lengths: 1/h of each direction, [dim][lanes];
     * volume: the cells' volumes, [lanes]; w, grad_w: the iterate at the Gauss points
     * (lexicographic), [n_points × dim][lanes] and [n_points × dim × dim][lanes] (row
     * ∂_e w_c at c dim + e), or nullptr for Stokes.
     */
    static void apply(const double *in, double *out, const double *inverse_lengths,
                      const double *volume, const double *w, const double *grad_w,
                      const double mass, const double density, const double viscosity);
  };
} // namespace fdparticle

#endif
