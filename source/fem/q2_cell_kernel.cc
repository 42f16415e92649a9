// Compiled for the build machine's instruction set (CMakeLists.txt): the vector type
// below becomes one AVX-512 register, or two AVX2 ones, and so on.

#include <fdparticle/fem/q2_cell_kernel.h>

#include <cmath>
#include <cstring>

namespace fdparticle
{
  namespace
  {
    using Lanes = double __attribute__((vector_size(8 * 8)));
    static_assert(sizeof(Lanes) == Q2CellKernel<3>::lanes * sizeof(double),
                  "one vector per lane set");

    /// The 1D data on [0, 1]: the Q2 basis (nodes 0, 1/2, 1) at the Gauss points (S), the
    /// derivatives of the Lagrange polynomials through the Gauss points there
    /// (collocation, C), and the Gauss weights.
    struct Basis
    {
      double S[3][3], C[3][3], weight[3];
      Basis()
      {
        const double g[3] = {0.5 - std::sqrt(15.0) / 10, 0.5, 0.5 + std::sqrt(15.0) / 10};
        const double node[3] = {0, 0.5, 1};
        for (unsigned int q = 0; q < 3; ++q)
          for (unsigned int i = 0; i < 3; ++i)
            {
              double value = 1, derivative = 0;
              for (unsigned int k = 0; k < 3; ++k)
                if (k != i)
                  value *= (g[q] - node[k]) / (node[i] - node[k]);
              // d/dx of the Lagrange polynomial through the Gauss points, at g[q].
              for (unsigned int k = 0; k < 3; ++k)
                if (k != i)
                  {
                    double term = 1 / (g[i] - g[k]);
                    for (unsigned int m = 0; m < 3; ++m)
                      if (m != i && m != k)
                        term *= (g[q] - g[m]) / (g[i] - g[m]);
                    derivative += term;
                  }
              S[q][i] = value;
              C[q][i] = derivative;
            }
        weight[0] = weight[2] = 5.0 / 18;
        weight[1] = 8.0 / 18;
      }
    };
    const Basis basis;

    /// y = M x along one direction of a 3^dim array (transpose: Mᵀ x; add: y += …); in
    /// place allowed.
    template <int dim, int direction, bool transpose, bool add>
    inline void apply_1d(const double (&M)[3][3], const Lanes *x, Lanes *y)
    {
      constexpr int stride = direction == 0 ? 1 : (direction == 1 ? 3 : 9);
      constexpr int n = dim == 2 ? 9 : 27;
      for (int outer = 0; outer < n / (3 * stride); ++outer)
        for (int inner = 0; inner < stride; ++inner)
          {
            const int   first = outer * 3 * stride + inner;
            const Lanes x0 = x[first], x1 = x[first + stride], x2 = x[first + 2 * stride];
            for (int q = 0; q < 3; ++q)
              {
                const Lanes r = transpose ? M[0][q] * x0 + M[1][q] * x1 + M[2][q] * x2 :
                                            M[q][0] * x0 + M[q][1] * x1 + M[q][2] * x2;
                if (add)
                  y[first + q * stride] += r;
                else
                  y[first + q * stride] = r;
              }
          }
    }

    template <int dim, bool transpose, bool add>
    inline void apply_along(const int direction, const double (&M)[3][3], const Lanes *x, Lanes *y)
    {
      if (direction == 0)
        apply_1d<dim, 0, transpose, add>(M, x, y);
      else if (direction == 1)
        apply_1d<dim, 1, transpose, add>(M, x, y);
      else if constexpr (dim == 3)
        apply_1d<dim, 2, transpose, add>(M, x, y);
    }

    inline Lanes load(const double *p)
    {
      Lanes v;
      std::memcpy(&v, p, sizeof(Lanes));
      return v;
    }
    inline void store(double *p, const Lanes &v) { std::memcpy(p, &v, sizeof(Lanes)); }
  } // namespace

  template <int dim>
  void Q2CellKernel<dim>::apply(const double *in, double *out, const double *inverse_lengths,
                                const double *volume, const double *w, const double *grad_w,
                                const double mass, const double density, const double viscosity)
  {
    constexpr int N = n_dofs, L = lanes;
    Lanes         u[dim][N], g[dim][dim][N], h[dim];
    for (int d = 0; d < dim; ++d)
      h[d] = load(inverse_lengths + d * L);
    const Lanes cell_volume = load(volume);

    // Values at the Gauss points, then their gradients by collocation.
    for (int c = 0; c < dim; ++c)
      {
        for (int i = 0; i < N; ++i)
          u[c][i] = load(in + (c * N + i) * L);
        for (int d = 0; d < dim; ++d)
          apply_along<dim, false, false>(d, basis.S, u[c], u[c]);
        for (int d = 0; d < dim; ++d)
          {
            apply_along<dim, false, false>(d, basis.C, u[c], g[c][d]);
            for (int q = 0; q < N; ++q)
              g[c][d][q] *= h[d];
          }
      }

    // The point terms, times JxW; the gradient terms also times ∂ξ_d/∂x_d for the
    // transposed derivative below.
    for (int q = 0; q < N; ++q)
      {
        const int qx = q % 3, qy = (q / 3) % 3, qz = q / 9;
        const double weight =
          basis.weight[qx] * basis.weight[qy] * (dim == 3 ? basis.weight[qz] : 1.0);
        const Lanes JxW = weight * cell_volume;
        Lanes       value[dim], flux[dim][dim];
        for (int c = 0; c < dim; ++c)
          {
            value[c] = mass * u[c][q];
            for (int d = 0; d < dim; ++d)
              flux[c][d] = viscosity * (g[c][d][q] + g[d][c][q]) * JxW * h[d];
          }
        if (w != nullptr)
          for (int c = 0; c < dim; ++c)
            {
              Lanes convection = {};
              for (int d = 0; d < dim; ++d)
                convection += g[c][d][q] * load(w + (q * dim + d) * L) +
                              load(grad_w + ((q * dim + c) * dim + d) * L) * u[d][q];
              value[c] += density * convection;
            }
        for (int c = 0; c < dim; ++c)
          {
            u[c][q] = value[c] * JxW;
            for (int d = 0; d < dim; ++d)
              g[c][d][q] = flux[c][d];
          }
      }

    // Integration: the transposed derivatives and values back to the shape functions.
    for (int c = 0; c < dim; ++c)
      {
        for (int d = 0; d < dim; ++d)
          apply_along<dim, true, true>(d, basis.C, g[c][d], u[c]);
        for (int d = 0; d < dim; ++d)
          apply_along<dim, true, false>(d, basis.S, u[c], u[c]);
        for (int i = 0; i < N; ++i)
          store(out + (c * N + i) * L, u[c][i]);
      }
  }

  template struct Q2CellKernel<2>;
  template struct Q2CellKernel<3>;
} // namespace fdparticle
