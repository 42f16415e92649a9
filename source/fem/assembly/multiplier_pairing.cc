#include <fdparticle/fem/assembly/multiplier_pairing.h>
#include <fdparticle/particles/rigid_body.h>

#include <array>
#include <cmath>

namespace fdparticle
{
  template <int dim>
  void MultiplierPairing<dim>::assemble_point(const AssemblyScratch<dim> &s,
                                              AssemblyCopy<dim> &         copy) const
  {
    const int k = s.particle;
    if (k < 0)
      return;
    using RB = RigidBody<dim>;
    const Particle<dim> &            P = particles[k];
    const double                     mu = fluid.viscosity, JxW = s.JxW;
    const double                     kappa = s.pairing_weight(P.bounding_radius());
    const auto &                     N = s.N;
    const auto &                     dN = s.dN;
    const std::vector<unsigned int> &comp = s.component;
    const Tensor<1, dim> &           l = s.lambda[s.q];
    const Tensor<2, dim> &           gl = s.grad_lambda[s.q];
    const Tensor<2, dim> &           gu = s.grad_u[s.q];

    // Residual: the rigidity (F3) in P_k, and the −<λ, v> term of the momentum equation.
    const Tensor<1, dim> r = P.offset(s.x);
    const Tensor<1, dim> du = s.u[s.q] - P.velocity - RB::cross(P.omega, r);
    const Tensor<2, dim> dgu = gu - RB::rotation_gradient(P.omega);
    for (const unsigned int i : s.velocity_dofs)
      copy.rhs(i) -= (kappa * l[comp[i]] * N[i] + mu * (gl[comp[i]] * dN[i])) * JxW;
    for (const unsigned int a : s.multiplier_dofs)
      copy.rhs(a) += (kappa * du[comp[a]] * N[a] + mu * (dgu[comp[a]] * dN[a])) * JxW;

    // The integrals of (F4)–(F5) and of the reported force and torque.
    ParticleIntegrals<dim> &I = copy.integrals[k];
    I.lambda_force += kappa * l * JxW;
    for (unsigned int j = 0; j < 3; ++j)
      {
        Tensor<1, 3> e;
        e[j] = 1;
        I.lambda_torque[j] +=
          (kappa * (l * RB::cross(e, r)) + mu * scalar_product(gl, RB::rotation_gradient(e))) * JxW;
      }
    I.curl_u += RB::curl(gu) * JxW;
    I.volume += JxW;

    // Jacobian: the pairing between λ and u is assembled per cell (assemble_cell_matrix).
    if (!s.with_matrix || P.first_unknown == numbers::invalid_unsigned_int)
      return;
    // Border: ∂(rigidity)/∂(V, ω) and ∂(particle rows)/∂(λ or u).
    const unsigned int n_rot = RB::n_rotations;
    auto &             B = copy.border_B[k];
    auto &             C = copy.border_C[k];
    // The rigid rotations about the axes: their velocity e_j × r and gradient at the point.
    std::array<Tensor<1, dim>, RB::n_rotations> rotation_velocity;
    std::array<Tensor<2, dim>, RB::n_rotations> rotation_gradient;
    for (unsigned int j = 0; j < n_rot; ++j)
      {
        rotation_velocity[j] = RB::cross(RB::rotation_axis(j), r);
        rotation_gradient[j] = RB::rotation_gradient(RB::rotation_axis(j));
      }
    for (const unsigned int a : s.multiplier_dofs)
      {
        const unsigned int ca = comp[a];
        B(a, ca) -= kappa * N[a] * JxW;
        C(a, ca) += kappa * N[a] * JxW;
        for (unsigned int j = 0; j < n_rot; ++j)
          {
            const double pairing =
              (kappa * N[a] * rotation_velocity[j][ca] + mu * (rotation_gradient[j][ca] * dN[a])) * JxW;
            B(a, dim + j) -= pairing;
            if (particles.closure() == AngularVelocityClosure::torque_balance)
              C(a, dim + j) += pairing;
          }
      }
    if (particles.closure() == AngularVelocityClosure::kinematic)
      for (const unsigned int b : s.velocity_dofs)
        {
          Tensor<2, dim> G;
          G[comp[b]] = dN[b];
          const Tensor<1, 3> curl = RB::curl(G);
          for (unsigned int j = 0; j < n_rot; ++j)
            C(b, dim + j) -= 0.5 * (curl * RB::rotation_axis(j)) * JxW;
        }
  }

  template <int dim>
  void MultiplierPairing<dim>::assemble_cell_matrix(const AssemblyScratch<dim> &s,
                                                    AssemblyCopy<dim> &         copy) const
  {
    if (!s.has_particle)
      return;
    // The pairing between λ and u, antisymmetric in sign, over the points inside particles:
    // Σ_q JxW (κ_k ψ_s φ_t + μ ∇ψ_s·∇φ_t), κ_k of the point's owner k. λ and u share their
    // scalar functions (ψ = φ), so it is the Gram matrix of the rows (√(κ_k JxW) φ,
    // √(μ JxW) ∂_0 φ, …), each feature a row of its own (a row of CellShapes read as dim + 1
    // rows of n_functions).
    const CellShapes<dim> &L = s.multiplier_shapes, &V = s.velocity_shapes;
    const unsigned int     nf = V.n_functions(), nc = V.n_columns();
    Assert(L.n_functions() == nf, ExcInternalError());
    const double         root_mu = std::sqrt(fluid.viscosity);
    std::vector<double> &weighted = copy.weighted;
    weighted.clear();
    for (unsigned int q = 0; q < V.n_points(); ++q)
      if (s.owners[q] >= 0)
        {
          const double root = std::sqrt(s.weights[q]);
          const double root_kappa = std::sqrt(s.pairing_weight(particles[s.owners[q]].bounding_radius()));
          for (unsigned int k = 0; k < nc; ++k)
            weighted.push_back((k < nf ? root_kappa : root_mu) * root * V.row(q)[k]);
        }
    std::vector<double> pairing(nf * nf, 0.0);
    add_gram(weighted.size() / nf, nf, weighted.data(), nf, pairing.data());
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int a = 0; a < nf; ++a)
        for (unsigned int b = 0; b < nf; ++b)
          {
            const double m = pairing[a * nf + b];
            copy.matrix(L.dof(c, a), V.dof(c, b)) += m;
            copy.matrix(V.dof(c, b), L.dof(c, a)) -= m;
          }
  }

  template class MultiplierPairing<2>;
  template class MultiplierPairing<3>;
} // namespace fdparticle
