#include <fdparticle/particles/contact_friction.h>
#include <fdparticle/particles/rigid_body.h>

#include <cmath>

namespace fdparticle
{
  template <int dim>
  ContactFriction<dim>::ContactFriction(const double coefficient, const double slip_velocity)
    : coefficient(coefficient)
    , slip_velocity(slip_velocity)
  {
    Assert(slip_velocity > 0, ExcMessage("The slip velocity must be positive."));
  }

  namespace
  {
    /// Set the velocity and angular velocity of P from u, starting at offset.
    template <int dim, typename Vector>
    void set_motion(Particle<dim> &P, const Vector &u, const unsigned int offset)
    {
      for (unsigned int d = 0; d < dim; ++d)
        P.velocity[d] = u[offset + d];
      for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
        P.omega[RigidBody<dim>::rotation_component(r)] = u[offset + dim + r];
    }
  } // namespace

  template <int dim>
  typename ContactFriction<dim>::PairVector
  ContactFriction<dim>::rows(const Particle<dim> &P_i, const Particle<dim> &P_j,
                             const Tensor<1, dim> &shift, const NormalForce &normal_force,
                             const std::array<double, 3> &c, const PairVector &u) const
  {
    Particle<dim> A = P_i, B = P_j;
    set_motion(A, u, 0);
    set_motion(B, u, n_unknowns);
    const Tensor<1, dim> offset = A.position_after_step(c) - B.position_after_step(c) + shift;
    const double         distance = offset.norm();
    const Tensor<1, dim> n = offset / distance;
    const double         gap = distance - A.radius - B.radius;
    const Tensor<1, dim> relative = A.velocity - B.velocity;
    const double         F_n = std::max(normal_force(gap, relative * n), 0.0);
    // The contact point is the middle of the gap: −(R_i + g/2) n from X_i, (R_j + g/2) n
    // from X_j. One point for both balls, so the pair's angular momentum is conserved.
    const Tensor<1, dim> arm_i = -(A.radius + gap / 2) * n, arm_j = (B.radius + gap / 2) * n;
    const Tensor<1, dim> sliding =
      relative + RigidBody<dim>::cross(A.omega, arm_i) - RigidBody<dim>::cross(B.omega, arm_j);
    const Tensor<1, dim> v_t = sliding - (sliding * n) * n;
    const Tensor<1, dim> F = -coefficient * F_n / std::sqrt(v_t.norm_square() +
                                                            slip_velocity * slip_velocity) * v_t;
    const Tensor<1, 3>   T_i = RigidBody<dim>::moment(arm_i, F);
    const Tensor<1, 3>   T_j = RigidBody<dim>::moment(arm_j, -F);
    PairVector result;
    for (unsigned int d = 0; d < dim; ++d)
      {
        result[d]              = F[d];
        result[n_unknowns + d] = -F[d];
      }
    for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
      {
        result[dim + r]              = T_i[RigidBody<dim>::rotation_component(r)];
        result[n_unknowns + dim + r] = T_j[RigidBody<dim>::rotation_component(r)];
      }
    return result;
  }

  template <int dim>
  void ContactFriction<dim>::add(ParticleSet<dim> &particles, const unsigned int i,
                                 const unsigned int j, const Tensor<1, dim> &shift,
                                 const NormalForce &normal_force,
                                 const std::array<double, 3> &c, Eigen::VectorXd &r_p,
                                 Eigen::SparseMatrix<double> *D) const
  {
    if (coefficient == 0)
      return;
    const std::array<unsigned int, 2>        ball{{i, j}};
    PairVector                        u;
    for (unsigned int s = 0; s < 2; ++s)
      {
        const Particle<dim> &P = particles[ball[s]];
        for (unsigned int d = 0; d < dim; ++d)
          u[s * n_unknowns + d] = P.velocity[d];
        for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
          u[s * n_unknowns + dim + r] = P.omega[RigidBody<dim>::rotation_component(r)];
      }
    const auto value = rows(particles[i], particles[j], shift, normal_force, c, u);
    for (unsigned int s = 0; s < 2; ++s)
      {
        Particle<dim> &P = particles[ball[s]];
        for (unsigned int d = 0; d < dim; ++d)
          P.contact_force[d] += value[s * n_unknowns + d];
        if (P.first_unknown == numbers::invalid_unsigned_int)
          continue;
        for (unsigned int k = 0; k < n_unknowns; ++k)
          r_p[P.first_unknown + k] -= value[s * n_unknowns + k];
      }
    if (D == nullptr)
      return;
    for (unsigned int t = 0; t < 2; ++t)
      {
        const unsigned int column = particles[ball[t]].first_unknown;
        if (column == numbers::invalid_unsigned_int)
          continue; // a fixed or prescribed ball's motion is no unknown
        for (unsigned int k = 0; k < n_unknowns; ++k)
          {
            const unsigned int entry = t * n_unknowns + k;
            const double step = difference_step * slip_velocity;
            auto         plus = u, minus = u;
            plus[entry] += step;
            minus[entry] -= step;
            const PairVector derivative = (rows(particles[i], particles[j], shift, normal_force, c, plus) -
                                     rows(particles[i], particles[j], shift, normal_force, c, minus)) /
                                    (2 * step);
            for (unsigned int s = 0; s < 2; ++s)
              {
                const unsigned int row = particles[ball[s]].first_unknown;
                if (row != numbers::invalid_unsigned_int)
                  for (unsigned int l = 0; l < n_unknowns; ++l)
                    D->coeffRef(row + l, column + k) -= derivative[s * n_unknowns + l];
              }
          }
      }
  }

  template class ContactFriction<2>;
  template class ContactFriction<3>;
} // namespace fdparticle
