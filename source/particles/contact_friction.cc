#include <fdparticle/particles/contact_friction.h>
#include <fdparticle/particles/contact_geometry.h>
#include <fdparticle/particles/rigid_body.h>

#include <array>
#include <cmath>

namespace fdparticle
{
  template <int dim>
  ContactFriction<dim>::ContactFriction(const double coefficient, const SpringDashpotLaw &spring)
    : coefficient(coefficient)
    , slip_velocity(slip_velocity_fraction * spring.range / spring.duration)
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
  ContactFriction<dim>::rows(const ParticleSet<dim> &particles, const unsigned int i,
                             const Partner &partner, const NormalForce &normal_force,
                             const std::array<double, 3> &c, const PairVector &u) const
  {
    const bool    is_pair = (partner.j != numbers::invalid_unsigned_int);
    Particle<dim> A = particles[i];
    set_motion(A, u, 0);
    const Point<dim> X_A = A.position_after_step(c);
    // The partner's velocity at its centre and at the contact point, and the geometry of
    // the contact at the end-of-step positions.
    Tensor<1, dim>       partner_velocity, partner_point_velocity;
    ContactGeometry<dim> contact;
    Tensor<1, dim>       arm_j;
    if (is_pair)
      {
        Particle<dim> B = particles[partner.j];
        set_motion(B, u, n_unknowns);
        contact = ContactGeometry<dim>::pair(A, B, X_A - B.position_after_step(c) + partner.shift);
        arm_j   = contact.arm_j + (contact.gap / 2) * contact.normal;
        partner_velocity       = B.velocity;
        partner_point_velocity = B.velocity + RigidBody<dim>::cross(B.omega, arm_j);
      }
    else
      {
        contact = ContactGeometry<dim>::wall(A, partner.normal,
                                             partner.normal * X_A - partner.plane -
                                               A.bounding_radius());
        partner_velocity = partner_point_velocity = partner.wall_velocity;
      }
    // The contact point is the middle of the gap, between the two surfaces' nearest
    // points: one point for both partners, so a pair's angular momentum is conserved.
    const Tensor<1, dim> &n     = contact.normal;
    const Tensor<1, dim>  arm_i = contact.arm_i - (contact.gap / 2) * n;
    const double F_n = std::max(normal_force(contact.gap, (A.velocity - partner_velocity) * n), 0.0);
    const Tensor<1, dim> sliding =
      A.velocity + RigidBody<dim>::cross(A.omega, arm_i) - partner_point_velocity;
    const Tensor<1, dim> v_t = sliding - (sliding * n) * n;
    const Tensor<1, dim> F = -coefficient * F_n / std::sqrt(v_t.norm_square() +
                                                            slip_velocity * slip_velocity) * v_t;
    PairVector result = PairVector::Zero();
    const Tensor<1, 3> T_i = RigidBody<dim>::moment(arm_i, F);
    for (unsigned int d = 0; d < dim; ++d)
      result[d] = F[d];
    for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
      result[dim + r] = T_i[RigidBody<dim>::rotation_component(r)];
    if (is_pair)
      {
        const Tensor<1, 3> T_j = RigidBody<dim>::moment(arm_j, -F);
        for (unsigned int d = 0; d < dim; ++d)
          result[n_unknowns + d] = -F[d];
        for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
          result[n_unknowns + dim + r] = T_j[RigidBody<dim>::rotation_component(r)];
      }
    return result;
  }

  template <int dim>
  void ContactFriction<dim>::add_pair(ParticleSet<dim> &particles, const unsigned int i,
                                      const unsigned int j, const Tensor<1, dim> &shift,
                                      const NormalForce &normal_force,
                                      const std::array<double, 3> &c, Eigen::VectorXd &r_p,
                                      Eigen::SparseMatrix<double> *D) const
  {
    Partner partner;
    partner.j     = j;
    partner.shift = shift;
    add(particles, i, partner, normal_force, c, r_p, D);
  }

  template <int dim>
  void ContactFriction<dim>::add_wall(ParticleSet<dim> &particles, const unsigned int i,
                                      const typename Box<dim>::WallGap &wall,
                                      const NormalForce &normal_force,
                                      const std::array<double, 3> &c, Eigen::VectorXd &r_p,
                                      Eigen::SparseMatrix<double> *D) const
  {
    Partner partner;
    partner.normal        = wall.normal;
    partner.wall_velocity = wall.velocity;
    partner.plane =
      wall.normal * particles[i].position_after_step(c) - particles[i].bounding_radius() - wall.gap;
    add(particles, i, partner, normal_force, c, r_p, D);
  }

  template <int dim>
  void ContactFriction<dim>::add(ParticleSet<dim> &particles, const unsigned int i,
                                 const Partner &partner, const NormalForce &normal_force,
                                 const std::array<double, 3> &c, Eigen::VectorXd &r_p,
                                 Eigen::SparseMatrix<double> *D) const
  {
    if (coefficient == 0)
      return;
    // The balls of the contact: i, and j unless the partner is a wall.
    const std::array<unsigned int, 2> ball{{i, partner.j}};
    const unsigned int n_balls = (partner.j == numbers::invalid_unsigned_int ? 1 : 2);
    PairVector         u       = PairVector::Zero();
    for (unsigned int s = 0; s < n_balls; ++s)
      {
        const Particle<dim> &P = particles[ball[s]];
        for (unsigned int d = 0; d < dim; ++d)
          u[s * n_unknowns + d] = P.velocity[d];
        for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
          u[s * n_unknowns + dim + r] = P.omega[RigidBody<dim>::rotation_component(r)];
      }
    const auto value = rows(particles, i, partner, normal_force, c, u);
    for (unsigned int s = 0; s < n_balls; ++s)
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
    const double step = difference_step * slip_velocity;
    for (unsigned int t = 0; t < n_balls; ++t)
      {
        const unsigned int column = particles[ball[t]].first_unknown;
        if (column == numbers::invalid_unsigned_int)
          continue; // a fixed or prescribed ball's motion is no unknown
        for (unsigned int k = 0; k < n_unknowns; ++k)
          {
            const unsigned int entry = t * n_unknowns + k;
            auto               plus = u, minus = u;
            plus[entry] += step;
            minus[entry] -= step;
            const PairVector derivative = (rows(particles, i, partner, normal_force, c, plus) -
                                           rows(particles, i, partner, normal_force, c, minus)) /
                                          (2 * step);
            for (unsigned int s = 0; s < n_balls; ++s)
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
