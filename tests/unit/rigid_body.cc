// Unit test of fdparticle::RigidBody<2> and RigidBody<3> (include/fdparticle/particles/rigid_body.h)
// and of the Sphere shape (include/fdparticle/particles/sphere.h).
//
// Every expected value is computed here independently of the library: cross products by
// the Levi-Civita symbol, gradients by central differences of that cross product, the
// rotation of a vector by Rodrigues' formula, volumes and moments of inertia by the
// textbook formulas. The program prints each check and returns 1 if any fails.

#include <deal.II/base/numbers.h>
#include <deal.II/base/tensor.h>

#include <fdparticle/particles/rigid_body.h>
#include <fdparticle/particles/sphere.h>

#include "unit_check.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{

  /// The Levi-Civita symbol ε_ijk for i, j, k in 0..2.
  double levi_civita(const unsigned int i, const unsigned int j, const unsigned int k)
  {
    return 0.5 * (double(int(j) - int(i)) * double(int(k) - int(i)) * double(int(k) - int(j)));
  }

  /// (a × b)_i = ε_ijk a_j b_k, written independently of the library.
  Tensor<1, 3> reference_cross(const Tensor<1, 3> &a, const Tensor<1, 3> &b)
  {
    Tensor<1, 3> c;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        for (unsigned int k = 0; k < 3; ++k)
          c[i] += levi_civita(i, j, k) * a[j] * b[k];
    return c;
  }

  template <int dim>
  Tensor<1, 3> lift(const Tensor<1, dim> &r)
  {
    Tensor<1, 3> r3;
    for (unsigned int d = 0; d < dim; ++d)
      r3[d] = r[d];
    return r3;
  }

  template <int dim>
  Tensor<1, dim> restrict_to_dim(const Tensor<1, 3> &v)
  {
    Tensor<1, dim> r;
    for (unsigned int d = 0; d < dim; ++d)
      r[d] = v[d];
    return r;
  }

  /// v rotated by the angle θ about the unit axis k (Rodrigues).
  Eigen::Vector3d rodrigues(const Eigen::Vector3d &v, const Eigen::Vector3d &k, const double theta)
  {
    return v * std::cos(theta) + k.cross(v) * std::sin(theta) +
           k * k.dot(v) * (1.0 - std::cos(theta));
  }

  /// Angle between the rotations of two unit quaternions (0 when they are the same rotation).
  double rotation_distance(const Eigen::Quaterniond &a, const Eigen::Quaterniond &b)
  {
    return (a.toRotationMatrix() - b.toRotationMatrix()).norm();
  }

  template <int dim>
  void test_algebra()
  {
    using RB = RigidBody<dim>;
    std::cout << "RigidBody<" << dim << ">: algebra" << std::endl;

    // Generic, non-symmetric data; in 2D the in-plane ω components must be ignored.
    const Tensor<1, 3> omega({0.7, -1.3, 2.1});
    Tensor<1, dim>     r, f;
    for (unsigned int d = 0; d < dim; ++d)
      {
        r[d] = 0.3 + 0.45 * d - 0.2 * d * d;
        f[d] = -1.1 + 0.8 * d + 0.35 * d * d;
      }
    // A 3D cross product with r_z = 0 (2D) restricted to the plane is the 2D ω_z e_z × r.
    Tensor<1, 3> omega_eff = omega;
    if (dim == 2)
      omega_eff[0] = omega_eff[1] = 0;

    check(RB::n_rotations == (dim == 2 ? 1u : 3u), "n_rotations");
    check(RB::n_unknowns == (dim == 2 ? 3u : 6u), "n_unknowns");
    for (unsigned int j = 0; j < RB::n_rotations; ++j)
      {
        Tensor<1, 3> e;
        e[dim == 2 ? 2 : j] = 1;
        check_close(RB::rotation_axis(j), e, 0.0, "rotation_axis(" + std::to_string(j) + ")");
      }

    // cross
    const Tensor<1, dim> v = RB::cross(omega, r);
    check_close(v, restrict_to_dim<dim>(reference_cross(omega_eff, lift<dim>(r))), 1e-14,
                "cross(omega, r) == Levi-Civita omega x r");
    if (dim == 2)
      check_close(v, Tensor<1, dim>({-omega[2] * r[1], omega[2] * r[0]}), 1e-14,
                  "2D cross(omega, r) == omega_z (-r_y, r_x)");
    check_close(v * r, 0.0, 1e-14, "cross(omega, r) is orthogonal to r");

    // rotation_gradient against central differences of x -> omega x (x - X)
    const Tensor<1, dim> X = 0.5 * f; // some centre
    const auto field = [&](const Tensor<1, dim> &x) {
      return restrict_to_dim<dim>(reference_cross(omega_eff, lift<dim>(x - X)));
    };
    const double   eps = 1e-3;
    Tensor<2, dim> grad_fd;
    for (unsigned int l = 0; l < dim; ++l)
      {
        Tensor<1, dim> e;
        e[l] = eps;
        const Tensor<1, dim> diff = (field(r + e) - field(r - e)) / (2 * eps);
        for (unsigned int i = 0; i < dim; ++i)
          grad_fd[i][l] = diff[i]; // W_il = d_l u_i
      }
    const Tensor<2, dim> W = RB::rotation_gradient(omega);
    check_close(W, grad_fd, 1e-10, "rotation_gradient(omega) == finite-difference gradient");
    check_close(W + transpose(W), Tensor<2, dim>(), 0.0, "rotation_gradient(omega) is skew");
    check_close(W * r, v, 1e-14, "rotation_gradient(omega) * r == cross(omega, r)");

    // curl
    Tensor<1, 3> two_omega = 2 * omega_eff;
    check_close(RB::curl(W), two_omega, 1e-14,
                dim == 3 ? "curl(rotation_gradient(omega)) == 2 omega" :
                           "curl(rotation_gradient(omega)) == 2 omega_z e_z");
    // curl of a general (non-skew) gradient: (d_y u_z - d_z u_y, d_z u_x - d_x u_z, d_x u_y - d_y u_x)
    Tensor<2, dim> G;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int l = 0; l < dim; ++l)
        G[i][l] = 1.0 + i + 3.0 * l * l - 0.5 * i * l; // G[i][l] = d_l u_i
    Tensor<1, 3> curl_ref;
    if (dim == 3)
      {
        curl_ref[0] = G[2 % dim][1] - G[1][2 % dim];
        curl_ref[1] = G[0][2 % dim] - G[2 % dim][0];
      }
    curl_ref[2] = G[1][0] - G[0][1];
    check_close(RB::curl(G), curl_ref, 1e-14, "curl(G) of a general gradient, hand formula");
    check_close(RB::curl(G + transpose(G)), Tensor<1, 3>(), 1e-14,
                "curl of a symmetric gradient is 0");

    // moment r x f
    const Tensor<1, 3> m = RB::moment(r, f);
    check_close(m, reference_cross(lift<dim>(r), lift<dim>(f)), 1e-14,
                "moment(r, f) == r x f (Levi-Civita)");
    if (dim == 2)
      check_close(m[2], r[0] * f[1] - r[1] * f[0], 1e-14, "2D moment z == r_x f_y - r_y f_x");
    // The torque of the rigid velocity field about an axis ⊥ r: r x (omega x r) = |r|^2 omega.
    Tensor<1, 3> axis_perp;
    if (dim == 2)
      axis_perp[2] = 1.7;
    else
      axis_perp = reference_cross(lift<dim>(r), Tensor<1, 3>({0.2, 0.9, -0.4})); // ⊥ r
    check_close(RB::moment(r, RB::cross(axis_perp, r)), r.norm_square() * axis_perp, 1e-13,
                "moment(r, cross(w, r)) == |r|^2 w for w perpendicular to r");

    // volume and inertia of the sphere (disk)
    for (const double R : {0.1, 1.0, 2.5})
      {
        const double vol = (dim == 2 ? numbers::PI * R * R : 4.0 / 3.0 * numbers::PI * R * R * R);
        const double J = (dim == 2 ? 0.5 * vol * R * R : 0.4 * vol * R * R);
        check_close(Sphere<dim>(R).volume(), vol, 1e-14 * vol,
                    std::string("volume(") + std::to_string(R) + ") == " +
                      (dim == 2 ? "pi R^2" : "4/3 pi R^3"));
        check_close(Sphere<dim>(R).inertia(), J, 1e-14 * J,
                    std::string("inertia(") + std::to_string(R) + ") == " +
                      (dim == 2 ? "(1/2)|P| R^2" : "(2/5)|P| R^2"));
      }
    // Independent cross-check: disk J = pi R^4 / 2, ball J = 8 pi R^5 / 15.
    check_close(Sphere<dim>(1.3).inertia(),
                dim == 2 ? numbers::PI * std::pow(1.3, 4) / 2 : 8 * numbers::PI * std::pow(1.3, 5) / 15,
                1e-12, "inertia(1.3) == pi R^4/2 (disk) or 8 pi R^5/15 (ball)");

    // The sphere's geometric queries, against |r| and R.
    const double      R = 0.7;
    const Sphere<dim> ball(R);
    check(ball.bounding_radius() == R && ball.inscribed_radius() == R,
          "bounding and inscribed radius are R");
    Tensor<1, dim> e;
    e[0] = 0.6;
    e[dim - 1] += 0.8; // |e| = 1 in 2D and 3D
    check(ball.contains(0.999 * R * e) && !ball.contains(1.001 * R * e),
          "contains: just inside yes, just outside no");
    check(ball.contains((1 + 1e-12) * R * e) && !ball.contains((1 + 1e-8) * R * e),
          "contains: within the surface tolerance counts as inside, beyond it not");
    check_close(ball.surface_distance(2 * R * e), R, 1e-14, "surface distance outside");
    check_close(ball.surface_distance(0.25 * R * e), -0.75 * R, 1e-14, "surface distance inside");
    const Point<dim> C = Point<dim>() + 0.3 * e;
    const auto       psi = ball.level_set(C);
    check_close(psi->value(C + R * e), 0, 1e-14, "level set zero on the surface");
    check(psi->value(C) < 0 && psi->value(C + 1.5 * R * e) > 0,
          "level set negative inside, positive outside");
    const double h = 1e-6;
    const Point<dim> x = C + 0.4 * e;
    Tensor<1, dim> fd;
    for (unsigned int d = 0; d < dim; ++d)
      {
        Tensor<1, dim> dx;
        dx[d] = h;
        fd[d] = (psi->value(x + dx) - psi->value(x - dx)) / (2 * h);
      }
    check_close(psi->gradient(x), fd, 1e-8, "level-set gradient = central differences");
  }

  template <int dim>
  void test_rotate()
  {
    using RB = RigidBody<dim>;
    std::cout << "RigidBody<" << dim << ">: rotate" << std::endl;

    // A quarter turn about z takes e_x to e_y.
    {
      const Eigen::Quaterniond q =
        RB::rotate(Eigen::Quaterniond::Identity(), Tensor<1, 3>({0, 0, numbers::PI / 2}), 1.0);
      const Eigen::Vector3d ex(1, 0, 0), ey(0, 1, 0);
      check((q * ex - ey).norm() < 1e-14, "rotate(I, (0,0,pi/2), 1) maps e_x to e_y");
      check((q * ey - Eigen::Vector3d(-1, 0, 0)).norm() < 1e-14,
            "rotate(I, (0,0,pi/2), 1) maps e_y to -e_x");
      check(std::abs(q.norm() - 1) < 1e-15, "quarter-turn quaternion has unit norm");
    }

    // ω = 0 leaves the orientation alone.
    {
      const Eigen::Quaterniond q0(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 2).normalized()));
      const Eigen::Quaterniond q = RB::rotate(q0, Tensor<1, 3>(), 0.5);
      check(rotation_distance(q, q0) == 0.0, "rotate(q, 0, dt) == q");
    }

    // ω in the world frame: rotate(q, ω, dt) v == Rodrigues(q v, ω/|ω|, |ω| dt) for a body vector v.
    const Tensor<1, 3> omega =
      (dim == 2 ? Tensor<1, 3>({0, 0, -1.9}) : Tensor<1, 3>({0.6, -1.1, 0.8}));
    const Eigen::Vector3d k(omega[0] / omega.norm(), omega[1] / omega.norm(),
                            omega[2] / omega.norm());
    const Eigen::Quaterniond q0 =
      (dim == 2 ? Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())) :
                  Eigen::Quaterniond(Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 3).normalized())));
    const double dt = 0.37;
    {
      const Eigen::Quaterniond q = RB::rotate(q0, omega, dt);
      double                   err = 0;
      for (const Eigen::Vector3d &v :
           {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0.3, -0.2, 0.7)})
        err = std::max(err, (q * v - rodrigues(q0 * v, k, omega.norm() * dt)).norm());
      check(err < 1e-14, "rotate(q, omega, dt) v == Rodrigues(q v, omega, |omega| dt)",
            "error " + std::to_string(err));
    }

    // Two half steps give the full step.
    {
      const Eigen::Quaterniond full = RB::rotate(q0, omega, dt);
      const Eigen::Quaterniond half = RB::rotate(RB::rotate(q0, omega, dt / 2), omega, dt / 2);
      const double             d = rotation_distance(full, half);
      check(d < 1e-14, "rotate(rotate(q, w, dt/2), w, dt/2) == rotate(q, w, dt)",
            "difference " + std::to_string(d));
    }

    // 10^4 small steps: unit norm throughout, and the accumulated rotation is the exact one.
    {
      const unsigned int n = 10000;
      const double       T = 2.3, h = T / n;
      Eigen::Quaterniond q = q0;
      double             max_norm_error = 0;
      for (unsigned int i = 0; i < n; ++i)
        {
          q = RB::rotate(q, omega, h);
          max_norm_error = std::max(max_norm_error, std::abs(q.norm() - 1.0));
        }
      check(max_norm_error < 1e-14, "unit norm over 10^4 small steps",
            "max | |q| - 1 | = " + std::to_string(max_norm_error));
      const Eigen::Vector3d v(0.3, -0.2, 0.7);
      const double          err = (q * v - rodrigues(q0 * v, k, omega.norm() * T)).norm();
      check(err < 1e-11, "10^4 small steps == one rotation by |omega| T",
            "error " + std::to_string(err));
    }

    // In 2D the rotation stays about z: e_z is fixed and the angle of e_x advances by ω_z dt.
    if (dim == 2)
      {
        const Eigen::Quaterniond q = RB::rotate(q0, omega, dt);
        check((q * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm() < 1e-14,
              "2D: e_z stays fixed");
        const Eigen::Vector3d ex = q * Eigen::Vector3d::UnitX();
        check_close(std::atan2(ex[1], ex[0]), 0.3 + omega[2] * dt, 1e-14,
                    "2D: angle of e_x == 0.3 + omega_z dt");
      }
  }
} // namespace

int main()
{
  try
    {
      test_algebra<2>();
      test_algebra<3>();
      test_rotate<2>();
      test_rotate<3>();
    }
  catch (const std::exception &exc)
    {
      std::cerr << "Unexpected exception: " << exc.what() << std::endl;
      return 2;
    }
  return unit_check::summary();
}
