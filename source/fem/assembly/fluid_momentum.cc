#include <fdparticle/fem/assembly/fluid_momentum.h>

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
    if (!s.with_matrix)
      return;

    // Jacobian.
    for (const unsigned int i : s.velocity_dofs)
      {
        const unsigned int ci = comp[i];
        for (const unsigned int j : s.velocity_dofs)
          {
            const unsigned int cj = comp[j];
            // 2μ ε(φ_j):ε(φ_i) = μ (δ ∇N_i·∇N_j + ∂_cj N_i ∂_ci N_j)
            double value = mu * dN[i][cj] * dN[j][ci];
            if (ci == cj)
              value += rho * c[0] * N[i] * N[j] + mu * (dN[i] * dN[j]) +
                       (fluid.convection ? rho * N[i] * (dN[j] * u) : 0.0);
            if (fluid.convection)
              value += rho * N[i] * gu[ci][cj] * N[j];
            copy.matrix(i, j) += value * JxW;
          }
        for (const unsigned int j : s.pressure_dofs)
          {
            const double b = -N[j] * dN[i][ci] * JxW;
            copy.matrix(i, j) += b;
            copy.matrix(j, i) += b;
          }
      }
  }

  template class FluidMomentum<2>;
  template class FluidMomentum<3>;
} // namespace fdparticle
