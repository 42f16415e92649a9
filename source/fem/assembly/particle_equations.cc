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
        const Tensor<1, 3>   dwdt = P.angular_acceleration(c);
        for (unsigned int d = 0; d < dim; ++d)
          {
            system.r_p[f + d] =
              drho * P.volume() * (dVdt[d] - fluid.gravity[d]) + integrals[k].lambda_force[d];
            if (with_matrix)
              system.D.coeffRef(f + d, f + d) = drho * P.volume() * c[0];
          }
        // (F5) with J = Q J_body Qᵀ: d(Jω)/dt = J dω/dt + ω × Jω, whose last term vanishes
        // for an isotropic J (a ball) and in 2D.
        const Tensor<2, 3> J = P.inertia();
        const bool         isotropic = P.shape->is_isotropic() || dim == 2;
        const Tensor<1, 3> Jw = J * P.omega;
        const Tensor<1, 3> angular_rate =
          isotropic ? Tensor<1, 3>() : J * dwdt + cross_product_3d(P.omega, Jw);
        for (unsigned int j = 0; j < RB::n_rotations; ++j)
          {
            const Tensor<1, 3> e = RB::rotation_axis(j);
            const unsigned int cj = RB::rotation_component(j);
            if (particles.closure() == AngularVelocityClosure::torque_balance && isotropic)
              {
                system.r_p[f + dim + j] =
                  drho * J[cj][cj] * (dwdt * e) + integrals[k].lambda_torque * e;
                if (with_matrix)
                  system.D.coeffRef(f + dim + j, f + dim + j) = drho * J[cj][cj] * c[0];
              }
            else if (particles.closure() == AngularVelocityClosure::torque_balance)
              {
                system.r_p[f + dim + j] = drho * angular_rate[cj] + integrals[k].lambda_torque * e;
                // ∂/∂ω of (c0 J ω + ω × Jω) = c0 J + [ω]× J − [Jω]×.
                if (with_matrix)
                  for (unsigned int m = 0; m < RB::n_rotations; ++m)
                    {
                      const Tensor<1, 3> em = RB::rotation_axis(m);
                      const Tensor<1, 3> column = c[0] * (J * em) +
                                                  cross_product_3d(P.omega, J * em) -
                                                  cross_product_3d(Jw, em);
                      system.D.coeffRef(f + dim + j, f + dim + m) = drho * column[cj];
                    }
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
