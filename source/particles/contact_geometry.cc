#include <fdparticle/particles/contact_geometry.h>

#include <deal.II/lac/full_matrix.h>

#include <array>
#include <cmath>
#include <limits>

namespace fdparticle
{
  template <int dim>
  ContactGeometry<dim> ContactGeometry<dim>::pair(const Particle<dim> &i, const Particle<dim> &j,
                                                  const Tensor<1, dim> &offset)
  {
    ContactGeometry<dim> c;
    const double         distance = offset.norm();
    Tensor<1, dim>       n = offset / distance;
    if (i.shape->is_isotropic() && j.shape->is_isotropic())
      {
        c.gap = distance - i.bounding_radius() - j.bounding_radius();
        c.normal = n;
        c.arm_i = -i.bounding_radius() * n;
        c.arm_j = j.bounding_radius() * n;
        return c;
      }
    // The gap along n, g(n) = n·d − h_i(−n) − h_j(n), is largest where its gradient
    // d + s_i − s_j (s the arms to the contact points) is parallel to n: a few ascent steps
    // toward the gradient's direction, then Newton's method on its tangential part, so
    // that n (the force's direction) is exact to round-off.
    const auto gradient = [&](const Tensor<1, dim> &m) {
      return offset + i.support_point(-m) - j.support_point(m);
    };
    const auto gap_along = [&](const Tensor<1, dim> &m) {
      return m * offset + m * i.support_point(-m) - m * j.support_point(m);
    };
    double gap = gap_along(n);
    for (unsigned int iteration = 0; iteration < 2000; ++iteration)
      {
        const Tensor<1, dim> ascent = gradient(n);
        const Tensor<1, dim> target = ascent / ascent.norm();
        Tensor<1, dim>       next = n;
        double               next_gap = gap;
        for (double step = 1; step > 1e-12; step /= 2)
          {
            Tensor<1, dim> m = n + step * (target - n);
            m /= m.norm();
            if (const double g = gap_along(m); g >= gap)
              {
                next = m;
                next_gap = g;
                break;
              }
          }
        const double moved = (next - n).norm();
        n = next;
        gap = next_gap;
        if (moved < 1e-6)
          break;
      }
    for (unsigned int iteration = 0; iteration < 20; ++iteration)
      {
        // Unit tangents t_k at n, and G_k = t_k · ∇g.
        std::array<Tensor<1, dim>, dim - 1> t;
        Tensor<1, dim> e;
        e[std::abs(n[0]) < 0.6 ? 0 : 1] = 1;
        t[0] = e - (e * n) * n;
        t[0] /= t[0].norm();
        if constexpr (dim == 3)
          t[1] = cross_product_3d(n, t[0]);
        // At m, the tangents t_k projected onto m's tangent plane: G vanishes where ∇g is
        // parallel to m. (Unprojected, G would vanish where ∇g is parallel to n, and its
        // derivative gain a term g I that turns Newton's step away from the maximum of a
        // long ellipsoid.)
        const auto tangential = [&](const Tensor<1, dim> &m) {
          const Tensor<1, dim> grad = gradient(m);
          Tensor<1, dim - 1>   G;
          for (unsigned int k = 0; k + 1 < dim; ++k)
            G[k] = (t[k] - (t[k] * m) * m) * grad;
          return G;
        };
        const Tensor<1, dim - 1> G = tangential(n);
        if (G.norm() <= 1e-14 * offset.norm())
          break;
        // Its derivative in the tangent coordinates by differences.
        constexpr double        h = 1e-7;
        FullMatrix<double>      J(dim - 1, dim - 1);
        for (unsigned int l = 0; l + 1 < dim; ++l)
          {
            Tensor<1, dim> m = n + h * t[l];
            m /= m.norm();
            const Tensor<1, dim - 1> Gl = tangential(m);
            for (unsigned int k = 0; k + 1 < dim; ++k)
              J(k, l) = (Gl[k] - G[k]) / h;
          }
        J.gauss_jordan();
        Tensor<1, dim> m = n;
        for (unsigned int k = 0; k + 1 < dim; ++k)
          for (unsigned int l = 0; l + 1 < dim; ++l)
            m -= J(k, l) * G[l] * t[k];
        m /= m.norm();
        // g is largest at the solution: a step that lowers it beyond round-off has left
        // Newton's region, and the ascent's n stands.
        if (gap_along(m) < gap - 1e-14 * offset.norm())
          break;
        n = m;
        gap = gap_along(n);
      }
    gap = gap_along(n);
    c.gap = gap;
    c.normal = n;
    c.arm_i = i.support_point(-n);
    c.arm_j = j.support_point(n);
    c.along_centres = false;
    return c;
  }

  template <int dim>
  ContactGeometry<dim> ContactGeometry<dim>::wall(const Particle<dim> &i,
                                                  const Tensor<1, dim> &normal,
                                                  const double          ball_gap)
  {
    ContactGeometry<dim> c;
    c.normal = normal;
    c.arm_i = i.support_point(-normal);
    c.along_centres = i.shape->is_isotropic();
    c.gap = c.along_centres ? ball_gap : ball_gap + i.bounding_radius() - i.extent(-normal);
    return c;
  }

  template struct ContactGeometry<2>;
  template struct ContactGeometry<3>;
} // namespace fdparticle
