#include <fdparticle/particles/normal_contact.h>

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
