#include <fdparticle/particles/normal_contact.h>
#include <fdparticle/particles/rigid_body.h>

namespace fdparticle
{
  template <int dim>
  NormalContact<dim> NormalContact<dim>::pair(const ParticleSet<dim> &particles,
                                              const unsigned int i, const unsigned int j,
                                              const Tensor<1, dim> &offset, const double gap)
  {
    NormalContact<dim> contact;
    contact.i                 = i;
    contact.j                 = j;
    contact.distance          = offset.norm();
    contact.n                 = offset / contact.distance;
    contact.g                 = gap;
    contact.relative_velocity = particles[i].velocity - particles[j].velocity;
    contact.v_n               = contact.relative_velocity * contact.n;
    return contact;
  }

  template <int dim>
  NormalContact<dim> NormalContact<dim>::wall(const ParticleSet<dim> &particles,
                                              const unsigned int i, const Tensor<1, dim> &normal,
                                              const double gap)
  {
    NormalContact<dim> contact;
    contact.i                 = i;
    contact.n                 = normal;
    contact.g                 = gap;
    contact.relative_velocity = particles[i].velocity;
    contact.v_n               = contact.relative_velocity * normal;
    return contact;
  }

  template <int dim>
  void NormalContact<dim>::add_shaped(
    ParticleSet<dim> &particles, const unsigned int i, const unsigned int j,
    const ContactGeometry<dim> &contact,
    const std::function<ContactGeometry<dim>(const Tensor<1, dim> &, const Tensor<1, dim> &)>
      &                                                           geometry,
    const std::function<NormalLawValue(double gap, double v_n)> &law, const double range,
    const std::array<double, 3> &c, Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D)
  {
    using RB = RigidBody<dim>;
    const unsigned int                n_balls = (j == numbers::invalid_unsigned_int ? 1 : 2);
    const std::array<unsigned int, 2> k{{i, j}};
    const bool torques = particles.closure() == AngularVelocityClosure::torque_balance;
    constexpr unsigned int n_rows = RB::n_unknowns;
    // Force and torque on each particle with the velocities moved by dV, at the contact
    // geometry of the positions they give.
    const auto evaluate = [&](const ContactGeometry<dim> &           at,
                              const std::array<Tensor<1, dim>, 2> &dV) {
      Tensor<1, dim> relative = particles[i].velocity + dV[0];
      if (n_balls == 2)
        relative -= particles[j].velocity + dV[1];
      const Tensor<1, dim> F = law(at.gap, relative * at.normal).force * at.normal;
      std::array<double, 2 * n_rows> rows{};
      for (unsigned int s = 0; s < n_balls; ++s)
        {
          const double         sign = (s == 0 ? 1.0 : -1.0);
          const Tensor<1, 3>   T = RB::moment(s == 0 ? at.arm_i : at.arm_j, sign * F);
          for (unsigned int d = 0; d < dim; ++d)
            rows[s * n_rows + d] = sign * F[d];
          for (unsigned int r = 0; r < RB::n_rotations; ++r)
            rows[s * n_rows + dim + r] = torques ? T[RB::rotation_component(r)] : 0.0;
        }
      return rows;
    };
    const auto at_rest = evaluate(contact, {});
    for (unsigned int s = 0; s < n_balls; ++s)
      {
        Particle<dim> &P = particles[k[s]];
        for (unsigned int d = 0; d < dim; ++d)
          P.contact_force[d] += at_rest[s * n_rows + d];
        if (P.first_unknown != numbers::invalid_unsigned_int)
          for (unsigned int q = 0; q < n_rows; ++q)
            r_p[P.first_unknown + q] -= at_rest[s * n_rows + q];
      }
    if (D == nullptr)
      return;
    const double step = 1e-6 * c[0] * range;
    for (unsigned int t = 0; t < n_balls; ++t)
      {
        const unsigned int column = particles[k[t]].first_unknown;
        if (column == numbers::invalid_unsigned_int)
          continue;
        for (unsigned int b = 0; b < dim; ++b)
          {
            std::array<Tensor<1, dim>, 2> plus{}, minus{};
            plus[t][b] = step;
            minus[t][b] = -step;
            const auto up = evaluate(geometry(plus[0] / c[0], plus[1] / c[0]), plus);
            const auto down = evaluate(geometry(minus[0] / c[0], minus[1] / c[0]), minus);
            for (unsigned int s = 0; s < n_balls; ++s)
              if (const unsigned int row = particles[k[s]].first_unknown;
                  row != numbers::invalid_unsigned_int)
                for (unsigned int q = 0; q < n_rows; ++q)
                  D->coeffRef(row + q, column + b) -=
                    (up[s * n_rows + q] - down[s * n_rows + q]) / (2 * step);
          }
      }
  }

  template <int dim>
  void NormalContact<dim>::add(ParticleSet<dim> &particles, const NormalLawValue &f,
                               const std::array<double, 3> &c, Eigen::VectorXd &r_p,
                               Eigen::SparseMatrix<double> *D) const
  {
    const Tensor<1, dim> F = f.force * n; // on i; −F on j
    Tensor<2, dim>       dF;              // dF/dV_rel
    Tensor<1, dim>       tangential_velocity;
    if (distance > 0)
      tangential_velocity = (relative_velocity - v_n * n) / distance;
    for (unsigned int a = 0; a < dim; ++a)
      for (unsigned int b = 0; b < dim; ++b)
        {
          const double nn = n[a] * n[b];
          double       by_position = f.d_gap * nn;
          if (distance > 0)
            by_position += f.force / distance * ((a == b ? 1.0 : 0.0) - nn) +
                           f.d_velocity * n[a] * tangential_velocity[b];
          dF[a][b] = by_position / c[0] + f.d_velocity * nn;
        }
    const unsigned int          n_balls = (j == numbers::invalid_unsigned_int ? 1 : 2);
    const std::array<unsigned int, 2> k{{i, j}};
    const std::array<double, 2>       sign{{1.0, -1.0}}; // ∂V_rel/∂V_k
    for (unsigned int s = 0; s < n_balls; ++s)
      {
        Particle<dim> &P = particles[k[s]];
        P.contact_force += sign[s] * F;
        if (P.first_unknown == numbers::invalid_unsigned_int)
          continue;
        for (unsigned int d = 0; d < dim; ++d)
          r_p[P.first_unknown + d] -= sign[s] * F[d];
        if (D != nullptr)
          for (unsigned int t = 0; t < n_balls; ++t)
            {
              const unsigned int column = particles[k[t]].first_unknown;
              if (column == numbers::invalid_unsigned_int)
                continue;
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int b = 0; b < dim; ++b)
                  D->coeffRef(P.first_unknown + a, column + b) -= sign[s] * sign[t] * dF[a][b];
            }
      }
  }

  template class NormalContact<2>;
  template class NormalContact<3>;
} // namespace fdparticle
