#include <fdparticle/particles/rigid_body.h>

#include <deal.II/base/numbers.h>

namespace fdparticle
{
  template <int dim>
  Tensor<1, 3> RigidBody<dim>::rotation_axis(const unsigned int j)
  {
    Assert(j < n_rotations, ExcIndexRange(j, 0, n_rotations));
    Tensor<1, 3> e;
    e[rotation_component(j)] = 1.0;
    return e;
  }

  template <int dim>
  Tensor<1, dim> RigidBody<dim>::cross(const Tensor<1, 3> &omega, const Tensor<1, dim> &r)
  {
    Tensor<1, dim> v;
    if constexpr (dim == 2)
      {
        v[0] = -omega[2] * r[1];
        v[1] = omega[2] * r[0];
      }
    else
      {
        v[0] = omega[1] * r[2] - omega[2] * r[1];
        v[1] = omega[2] * r[0] - omega[0] * r[2];
        v[2] = omega[0] * r[1] - omega[1] * r[0];
      }
    return v;
  }

  template <int dim>
  Tensor<2, dim> RigidBody<dim>::rotation_gradient(const Tensor<1, 3> &omega)
  {
    // (ω × r)_i = ε_ijl ω_j r_l, so ∂_l (ω × r)_i = ε_ijl ω_j: a skew matrix.
    Tensor<2, dim> W;
    if constexpr (dim == 2)
      {
        W[0][1] = -omega[2];
        W[1][0] = omega[2];
      }
    else
      {
        W[0][1] = -omega[2];
        W[0][2] = omega[1];
        W[1][0] = omega[2];
        W[1][2] = -omega[0];
        W[2][0] = -omega[1];
        W[2][1] = omega[0];
      }
    return W;
  }

  template <int dim>
  Tensor<1, 3> RigidBody<dim>::moment(const Tensor<1, dim> &r, const Tensor<1, dim> &f)
  {
    Tensor<1, 3> m;
    if constexpr (dim == 2)
      m[2] = r[0] * f[1] - r[1] * f[0];
    else
      {
        m[0] = r[1] * f[2] - r[2] * f[1];
        m[1] = r[2] * f[0] - r[0] * f[2];
        m[2] = r[0] * f[1] - r[1] * f[0];
      }
    return m;
  }

  template <int dim>
  Tensor<1, 3> RigidBody<dim>::curl(const Tensor<2, dim> &G)
  {
    Tensor<1, 3> c;
    if constexpr (dim == 2)
      c[2] = G[1][0] - G[0][1];
    else
      {
        c[0] = G[2][1] - G[1][2];
        c[1] = G[0][2] - G[2][0];
        c[2] = G[1][0] - G[0][1];
      }
    return c;
  }

  template <int dim>
  Eigen::Quaterniond RigidBody<dim>::rotate(const Eigen::Quaterniond &q,
                                            const Tensor<1, 3> &      omega,
                                            const double              dt)
  {
    const double angle = omega.norm() * dt;
    if (angle == 0.0)
      return q;
    const Eigen::Vector3d axis(omega[0] / omega.norm(),
                               omega[1] / omega.norm(),
                               omega[2] / omega.norm());
    Eigen::Quaterniond result = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)) * q;
    result.normalize();
    return result;
  }

  template <int dim>
  Tensor<1, 3> RigidBody<dim>::rotation_vector(const Eigen::Quaterniond &q)
  {
    const Eigen::AngleAxisd turn(q);
    Tensor<1, 3>            v;
    for (unsigned int d = 0; d < 3; ++d)
      v[d] = turn.angle() * turn.axis()[d];
    return v;
  }

  template <int dim>
  template <int n>
  Tensor<2, n> RigidBody<dim>::rotation_matrix(const Eigen::Quaterniond &q)
  {
    const Eigen::Matrix3d R = q.toRotationMatrix();
    Tensor<2, n>          Q;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        Q[i][j] = R(i, j);
    return Q;
  }

  template struct RigidBody<2>;
  template struct RigidBody<3>;
  template Tensor<2, 2> RigidBody<2>::rotation_matrix<2>(const Eigen::Quaterniond &);
  template Tensor<2, 3> RigidBody<2>::rotation_matrix<3>(const Eigen::Quaterniond &);
  template Tensor<2, 3> RigidBody<3>::rotation_matrix<3>(const Eigen::Quaterniond &);
} // namespace fdparticle
