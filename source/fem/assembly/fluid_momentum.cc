#include <fdparticle/fem/assembly/fluid_momentum.h>

#include <cmath>

namespace fdparticle
{
  template <int dim>
  void FluidMomentum<dim>::assemble_point(const AssemblyScratch<dim> &s,
                                          AssemblyCopy<dim> &         copy) const
  {
    const double                       rho = fluid.density, mu = fluid.viscosity;
    const auto &                       c = s.c;
    const auto &                       N = s.N;
    const auto &                       dN = s.dN;
    const std::vector<unsigned int> &  comp = s.component;
    const Tensor<1, dim> &             u = s.u[s.q];
    const Tensor<2, dim> &             gu = s.grad_u[s.q];
    const double                       JxW = s.JxW;

    // Residual. ρ g + f is the gradient of the hydrostatic pressure: a fluid at rest
    // balances it with ∇p alone.
    const Tensor<1, dim> convection = (fluid.convection ? gu * u : Tensor<1, dim>());
    const Tensor<1, dim> m_force =
      rho * (c[0] * u + s.u_history[s.q] + convection) - fluid.hydrostatic_gradient();
    const Tensor<2, dim> two_mu_eps = mu * (gu + transpose(gu));
    const double         div_u = trace(gu);
    for (const unsigned int i : s.velocity_dofs)
      copy.rhs(i) +=
        (m_force[comp[i]] * N[i] + two_mu_eps[comp[i]] * dN[i] - s.p[s.q] * dN[i][comp[i]]) * JxW;
    for (const unsigned int i : s.pressure_dofs)
      copy.rhs(i) -= N[i] * div_u * JxW;
  }

  template <int dim>
  void FluidMomentum<dim>::assemble_cell_matrix(const AssemblyScratch<dim> &s,
                                                AssemblyCopy<dim> &         copy) const
  {
    const double           rho = fluid.density, mu = fluid.viscosity, c0 = s.c[0];
    const CellShapes<dim> &V  = s.velocity_shapes;
    const unsigned int     nq = V.n_points(), nf = V.n_functions(), nc = V.n_columns();

    // The mass matrix Σ_q JxW φ_s φ_t and every Σ_q JxW ∂_d φ_s ∂_e φ_t, as Gram matrices
    // of the rows scaled by √JxW.
    std::vector<double> &weighted = copy.weighted;
    weighted.resize(nq * nc);
    for (unsigned int q = 0; q < nq; ++q)
      {
        const double root = std::sqrt(s.weights[q]);
        for (unsigned int k = 0; k < nc; ++k)
          weighted[q * nc + k] = root * V.row(q)[k];
      }
    std::vector<double> mass(nf * nf, 0.0), derivatives(dim * nf * dim * nf, 0.0);
    add_gram(nq, nf, weighted.data(), nc, mass.data());
    add_gram(nq, dim * nf, weighted.data() + V.column(1, 0), nc, derivatives.data());
    const auto D = [&](const unsigned int d, const unsigned int a, const unsigned int e,
                       const unsigned int b) { return derivatives[(d * nf + a) * dim * nf + e * nf + b]; };

    // Convection, Σ_q JxW φ_s [(u·∇)φ_t, ∂_b u_a φ_t]: column block 0 and 1 + a·dim + b.
    const unsigned int   n_blocks = 1 + dim * dim;
    std::vector<double> &convection = copy.product;
    if (fluid.convection)
      {
        weighted.resize(nq * n_blocks * nf);
        for (unsigned int q = 0; q < nq; ++q)
          {
            const double *x = V.row(q);
            double *      z = &weighted[q * n_blocks * nf];
            for (unsigned int t = 0; t < nf; ++t)
              {
                double u_grad = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  u_grad += s.u[q][d] * x[V.column(1 + d, t)];
                z[t] = s.weights[q] * u_grad;
                for (unsigned int a = 0; a < dim; ++a)
                  for (unsigned int b = 0; b < dim; ++b)
                    z[(1 + a * dim + b) * nf + t] = s.weights[q] * s.grad_u[q][a][b] * x[t];
              }
          }
        convection.assign(nf * n_blocks * nf, 0.0);
        add_transpose_product(nq, nf, n_blocks * nf, 1.0, V.data(), nc, weighted.data(),
                              n_blocks * nf, convection.data(), n_blocks * nf);
      }

    // 2μ ε(φ_j):ε(φ_i) = μ (δ ∇N_i·∇N_j + ∂_cj N_i ∂_ci N_j), plus ρ c0 and convection.
    for (unsigned int ci = 0; ci < dim; ++ci)
      for (unsigned int cj = 0; cj < dim; ++cj)
        for (unsigned int a = 0; a < nf; ++a)
          for (unsigned int b = 0; b < nf; ++b)
            {
              double value = mu * D(cj, a, ci, b);
              if (ci == cj)
                {
                  value += rho * c0 * mass[a * nf + b];
                  for (unsigned int d = 0; d < dim; ++d)
                    value += mu * D(d, a, d, b);
                  if (fluid.convection)
                    value += rho * convection[a * n_blocks * nf + b];
                }
              if (fluid.convection)
                value += rho * convection[a * n_blocks * nf + (1 + ci * dim + cj) * nf + b];
              copy.matrix(V.dof(ci, a), V.dof(cj, b)) += value;
            }

    // −∫ q ∇·v in both places: Σ_q JxW ∂_c φ_s ψ_j.
    const unsigned int n_p = s.pressure_dofs.size();
    weighted.resize(nq * n_p);
    for (unsigned int q = 0; q < nq; ++q)
      for (unsigned int j = 0; j < n_p; ++j)
        weighted[q * n_p + j] = s.weights[q] * s.pressure_values[q * n_p + j];
    std::vector<double> divergence(dim * nf * n_p, 0.0);
    add_transpose_product(nq, dim * nf, n_p, 1.0, V.data() + V.column(1, 0), nc, weighted.data(),
                          n_p, divergence.data(), n_p);
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int a = 0; a < nf; ++a)
        for (unsigned int j = 0; j < n_p; ++j)
          {
            const double b = -divergence[(c * nf + a) * n_p + j];
            copy.matrix(V.dof(c, a), s.pressure_dofs[j]) += b;
            copy.matrix(s.pressure_dofs[j], V.dof(c, a)) += b;
          }
  }

  template class FluidMomentum<2>;
  template class FluidMomentum<3>;
} // namespace fdparticle
