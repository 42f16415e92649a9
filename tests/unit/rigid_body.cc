// Unit test of fdparticle::RigidBody<2> and RigidBody<3> (include/fdparticle/particles/rigid_body.h)
// and of the Sphere and Ellipsoid shapes (include/fdparticle/particles/sphere.h, ellipsoid.h).
//
// Every expected value is computed here independently of the library: cross products by
// the Levi-Civita symbol, gradients by central differences of that cross product, the
// rotation of a vector by Rodrigues' formula and by the quaternion product q v q*, volumes
// and moments of inertia by the textbook formulas; whether an ellipsoid meets a box by
// sampling the box. The program prints each check and returns 1 if any fails.

#include <deal.II/base/numbers.h>
#include <deal.II/base/tensor.h>

#include <fdparticle/particles/ellipsoid.h>
#include <fdparticle/particles/rigid_body.h>
#include <fdparticle/particles/sphere.h>

#include "unit_check.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
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
        check_close(Sphere<dim>(R).inertia()[2][2], J, 1e-14 * J,
                    std::string("inertia(") + std::to_string(R) + ") == " +
                      (dim == 2 ? "(1/2)|P| R^2" : "(2/5)|P| R^2"));
      }
    // Independent cross-check: disk J = pi R^4 / 2, ball J = 8 pi R^5 / 15.
    check_close(Sphere<dim>(1.3).inertia()[2][2],
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
    const auto       psi = ball.level_set(C, Tensor<2, dim>(unit_symmetric_tensor<dim>()));
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

  /// q v q* by the Hamilton product of the quaternions (w, x, y, z), v = (0, v).
  std::array<double, 3> hamilton_rotate(const Eigen::Quaterniond &q, const std::array<double, 3> &v)
  {
    using Q4 = std::array<double, 4>;
    const auto product = [](const Q4 &a, const Q4 &b) {
      return Q4{{a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                 a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                 a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                 a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]}};
    };
    const Q4 p{{q.w(), q.x(), q.y(), q.z()}}, conjugate{{q.w(), -q.x(), -q.y(), -q.z()}};
    const Q4 r = product(product(p, Q4{{0, v[0], v[1], v[2]}}), conjugate);
    return {{r[1], r[2], r[3]}};
  }

  /// RigidBody::rotation_matrix<n>(q) is orthogonal with determinant 1 and maps v to q v q*.
  template <int dim, int n>
  void check_rotation_matrix(const Eigen::Quaterniond &q, const std::string &what)
  {
    const Tensor<2, n> Q = RigidBody<dim>::template rotation_matrix<n>(q);
    check_close(transpose(Q) * Q, Tensor<2, n>(unit_symmetric_tensor<n>()), 1e-14,
                what + ": Q^T Q = I");
    check_close(determinant(Q), 1.0, 1e-14, what + ": det Q = 1");
    double err = 0;
    for (const std::array<double, 3> &v :
         {std::array<double, 3>{{1, 0, 0}}, std::array<double, 3>{{0, 1, 0}},
          std::array<double, 3>{{0.3, -0.2, 0.7}}})
      {
        Tensor<1, n> vn;
        for (unsigned int d = 0; d < n; ++d)
          vn[d] = v[d];
        // The n = 2 block turns the in-plane part of v: v with its z dropped.
        const std::array<double, 3> expected =
          hamilton_rotate(q, n == 2 ? std::array<double, 3>{{v[0], v[1], 0}} : v);
        const Tensor<1, n> turned = Q * vn;
        for (unsigned int d = 0; d < n; ++d)
          err = std::max(err, std::abs(turned[d] - expected[d]));
      }
    check(err < 1e-14, what + ": Q v = q v q* (Hamilton product)", "error " + sci(err));
  }

  template <int dim>
  void test_rotation_matrix()
  {
    std::cout << "RigidBody<" << dim << ">: rotation_matrix" << std::endl;
    const std::string D = std::to_string(dim) + "D: ";
    // Turns of several angles, also past pi, about z (2D) or a skew axis (3D).
    const Eigen::Vector3d axis =
      dim == 2 ? Eigen::Vector3d(0, 0, 1) : Eigen::Vector3d(1, -2, 3).normalized();
    for (const double angle : {0.0, 0.4, 2.5, 4.0})
      {
        const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, axis));
        const std::string        what = D + "angle " + std::to_string(angle);
        check_rotation_matrix<dim, dim>(q, what);
        if (dim == 2)
          check_rotation_matrix<dim, 3>(q, what + " (3 x 3)");
      }
  }
} // namespace

namespace
{
  /// The Ellipsoid's geometry, turned by a rotation Q: its axes, a ball of equal axes,
  /// meets() against sampling the box, the level set's derivatives against central
  /// differences, and the height direction against the gradient sampled on the box.
  template <int dim>
  void test_ellipsoid()
  {
    std::cout << "Ellipsoid<" << dim << ">" << std::endl;
    const std::string   D = std::to_string(dim) + "D: ";
    Tensor<1, dim>      a;
    for (unsigned int d = 0; d < dim; ++d)
      a[d] = 0.5 - 0.15 * d;
    const Ellipsoid<dim> shape(a, "test");
    const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.7, dim == 2 ? Eigen::Vector3d(0, 0, 1) :
                                       Eigen::Vector3d(1, -2, 2).normalized())
        .toRotationMatrix();
    Tensor<2, dim> Q;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        Q[i][j] = R(i, j);
    check(shape.bounding_radius() == 0.5 && shape.inscribed_radius() == a[dim - 1],
          D + "bounding and inscribed radius are the largest and smallest semi-axis");
    for (unsigned int d = 0; d < dim; ++d)
      {
        Tensor<1, dim> e;
        e[d] = 1;
        check(shape.contains(0.999 * a[d] * e) && !shape.contains(1.001 * a[d] * e),
              D + "contains: along body axis " + std::to_string(d) + " up to a_" + std::to_string(d));
        check_close(shape.surface_distance(1.5 * a[d] * e), 0.5 * a[d], 1e-14,
                    D + "surface distance along a body axis");
      }
    try
      {
        Tensor<1, dim> bad = a;
        bad[0] = 0;
        Ellipsoid<dim> none(bad, "Particles/Particles (entry 1)");
        check(false, D + "a zero semi-axis is refused");
      }
    catch (const std::exception &e)
      {
        check(std::string(e.what()).find("entry 1") != std::string::npos,
              D + "a zero semi-axis is refused, naming the entry");
      }

    // A ball of equal semi-axes: the sphere's answers.
    Tensor<1, dim> equal;
    for (unsigned int d = 0; d < dim; ++d)
      equal[d] = 0.3;
    const Ellipsoid<dim> round(equal, "test");
    const Sphere<dim>    ball(0.3);
    check_close(round.volume(), ball.volume(), 1e-15, D + "equal semi-axes: the ball's volume");
    // 2D uses only J_zz (the lamina's in-plane entries are not the disk's).
    if (dim == 2)
      check_close(round.inertia()[2][2], ball.inertia()[2][2], 1e-15,
                  D + "equal semi-axes: the ball's inertia");
    else
      check_close(round.inertia(), ball.inertia(), 1e-15, D + "equal semi-axes: the ball's inertia");

    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> u(-0.6, 0.4), size(0.02, 0.4);
    const Point<dim>                       X;
    unsigned int n_boxes = 0, n_meeting = 0, wrong_meets = 0, wrong_height = 0, n_height = 0,
                 round_differs = 0;
    for (unsigned int b = 0; b < 400; ++b)
      {
        Point<dim> lo, hi;
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] = u(rng);
            hi[d] = lo[d] + size(rng);
          }
        const BoundingBox<dim> box(std::make_pair(lo, hi));
        // ψ on a grid of the box: its smallest value, and the gradient's range.
        const unsigned int n = (dim == 2 ? 60 : 24);
        double             lowest = 1e300;
        Tensor<1, dim>     g_min, g_max;
        double             g_norm = 0;
        const auto         psi = shape.level_set(X, Q);
        for (unsigned int i = 0; i < std::pow(n + 1, dim); ++i)
          {
            Point<dim>   x;
            unsigned int rest = i;
            for (unsigned int d = 0; d < dim; ++d, rest /= (n + 1))
              x[d] = lo[d] + (hi[d] - lo[d]) * double(rest % (n + 1)) / n;
            lowest = std::min(lowest, psi->value(x));
            const Tensor<1, dim> g = psi->gradient(x);
            g_norm = std::max(g_norm, g.norm());
            for (unsigned int d = 0; d < dim; ++d)
              {
                g_min[d] = (i == 0 ? g[d] : std::min(g_min[d], g[d]));
                g_max[d] = (i == 0 ? g[d] : std::max(g_max[d], g[d]));
              }
          }
        ++n_boxes;
        const bool meets = shape.meets(box, X, Q);
        n_meeting += meets;
        // A grid point inside: the box meets it. The grid's lowest ψ well above 0 (by more
        // than ψ can dip between grid points): it does not.
        if ((lowest < -1e-3 && !meets) || (lowest > 0.05 && meets))
          ++wrong_meets;
        if (shape.has_height_direction(box, X, Q, 0.2))
          {
            ++n_height;
            bool some = false;
            for (unsigned int d = 0; d < dim; ++d)
              some = some || std::max(g_min[d], -g_max[d]) >= 0.2 * g_norm * (1 - 1e-12);
            wrong_height += !some;
          }
        round_differs += (round.has_height_direction(box, X, Q, 0.2) !=
                          ball.has_height_direction(box, X, Q, 0.2)) +
                         (round.meets(box, X, Q) != (std::sqrt([&] {
                            double d2 = 0;
                            for (unsigned int d = 0; d < dim; ++d)
                              d2 += std::pow(std::max({lo[d] - X[d], 0.0, X[d] - hi[d]}), 2);
                            return d2;
                          }()) < 0.3 * (1 - 1e-10)));
      }
    check(n_meeting > 40 && n_meeting < n_boxes - 40,
          D + "the random boxes are mixed: " + std::to_string(n_meeting) + " of " +
            std::to_string(n_boxes) + " meet the ellipsoid");
    check(wrong_meets == 0, D + "meets() agrees with ψ sampled on the box",
          std::to_string(wrong_meets) + " boxes differ");
    check(n_height > 20 && wrong_height == 0,
          D + "a height direction where the sampled gradient has one (" +
            std::to_string(n_height) + " boxes)",
          std::to_string(wrong_height) + " boxes without");
    check(round_differs == 0, D + "equal semi-axes: the ball's height directions and boxes met");

    // The level set's derivatives, turned, against central differences.
    const Point<dim> C = Point<dim>() + 0.1 * Q[0];
    const auto       psi = shape.level_set(C, Q);
    Tensor<1, dim>   on;
    for (unsigned int d = 0; d < dim; ++d)
      on[d] = Q[d][1] * a[1];
    check_close(psi->value(C + on), 0.0, 1e-14, D + "level set zero at C + Q a_1 e_1");
    const double     h = 1e-5;
    const Point<dim> x = C + 0.2 * Q[1] - 0.1 * Q[0];
    Tensor<1, dim>   fd;
    Tensor<2, dim>   fd2;
    for (unsigned int d = 0; d < dim; ++d)
      {
        Tensor<1, dim> dx;
        dx[d] = h;
        fd[d] = (psi->value(x + dx) - psi->value(x - dx)) / (2 * h);
        const Tensor<1, dim> dg = (psi->gradient(x + dx) - psi->gradient(x - dx)) / (2 * h);
        for (unsigned int e = 0; e < dim; ++e)
          fd2[e][d] = dg[e];
      }
    check_close(psi->gradient(x), fd, 1e-8, D + "level-set gradient = central differences");
    check_close(Tensor<2, dim>(psi->hessian(x)), fd2, 1e-7, D + "level-set Hessian = central differences");
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
      test_rotation_matrix<2>();
      test_rotation_matrix<3>();
      test_ellipsoid<2>();
      test_ellipsoid<3>();
    }
  catch (const std::exception &exc)
    {
      std::cerr << "Unexpected exception: " << exc.what() << std::endl;
      return 2;
    }
  return unit_check::summary();
}
