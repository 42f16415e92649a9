#include <fdparticle/fem/assembly/particle_equations.h>
#include <fdparticle/particles/rigid_body.h>

namespace fdparticle
{
  template <int dim>
  void ParticleEquations<dim>::assemble(const std::vector<ParticleIntegrals<dim>> &integrals,
                                        const std::array<double, 3> &c, const bool with_matrix,
                                        NewtonSystem &system) const
  {
    using RB = RigidBody<dim>;
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const Particle<dim> &P = particles[k];
        if (P.first_unknown == numbers::invalid_unsigned_int)
          continue;
        const unsigned int   f = P.first_unknown;
        const double         drho = P.density - fluid.density;
        const Tensor<1, dim> dVdt = P.acceleration(c);
        for (unsigned int d = 0; d < dim; ++d)
          {
            system.r_p[f + d] =
              drho * P.volume() * (dVdt[d] - fluid.gravity[d]) + integrals[k].lambda_force[d];
            if (with_matrix)
              system.D.coeffRef(f + d, f + d) = drho * P.volume() * c[0];
          }
        // (F5): (ρ_k − ρ_f) d(Jω)/dt + <λ, θ × r> = 0 (Particle::angular_momentum_rate).
        const bool torque_balance = particles.closure() == AngularVelocityClosure::torque_balance;
        const Tensor<1, 3> rate = torque_balance ? P.angular_momentum_rate(c, drho) : Tensor<1, 3>();
        const Tensor<2, 3> rate_derivative = (torque_balance && with_matrix) ?
                                               P.angular_momentum_rate_derivative(c, drho) :
                                               Tensor<2, 3>();
        for (unsigned int j = 0; j < RB::n_rotations; ++j)
          {
            const Tensor<1, 3> e = RB::rotation_axis(j);
            const unsigned int cj = RB::rotation_component(j);
            if (torque_balance)
              {
                system.r_p[f + dim + j] = rate[cj] + integrals[k].lambda_torque * e;
                // With constant inertia the rate couples ω_j to itself only.
                if (with_matrix)
                  for (unsigned int m = 0; m < RB::n_rotations; ++m)
                    if (const unsigned int cm = RB::rotation_component(m);
                        m == j || !P.constant_inertia())
                      system.D.coeffRef(f + dim + j, f + dim + m) = rate_derivative[cj][cm];
              }
            else
              {
                system.r_p[f + dim + j] =
                  integrals[k].volume * (P.omega * e) - 0.5 * (integrals[k].curl_u * e);
                if (with_matrix)
                  system.D.coeffRef(f + dim + j, f + dim + j) = integrals[k].volume;
              }
          }
      }
  }

  template class ParticleEquations<2>;
  template class ParticleEquations<3>;
} // namespace fdparticle
