// Unit test of fdparticle::PairSearch and fdparticle::Collisions, in 2D and 3D
// (include/fdparticle/particles/pair_search.h, collisions.h).
//
// PairSearch is compared with the comparison of all pairs, done here with the nearest
// periodic image found by trying every shift by a box length. The collision force of the
// particle rows is checked for being equal and opposite on a pair and zero out of range, and
// its derivative in the particle block D against central differences of the residual in
// the particle velocities. The program prints each check and returns 1 if any fails.

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/base/fluid.h>
#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/particles/collisions.h>
#include <fdparticle/particles/contact_geometry.h>
#include <fdparticle/particles/ellipsoid.h>
#include <fdparticle/particles/lubrication.h>
#include <fdparticle/particles/pair_search.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/particles/sphere.h>
#include <fdparticle/particles/wall_repulsion.h>

#include "unit_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <utility>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  /// Step of the central differences in the velocities, and the agreement asked of them
  /// relative to the largest entry of D: the force is smooth inside the range, so only the
  /// O(step²) truncation and round-off limit it.
  constexpr double fd_step      = 1e-7;
  constexpr double fd_tolerance = 1e-6;

  /// The subsection Collisions of each test unless it gives its own.
  const std::string repulsion = "  set Model = repulsion\n  set Range = 0.05\n";
  const std::string none_model = "  set Model = none\n";

  template <int dim>
  void parse(ParameterHandler &prm, const std::string &periodic, const std::string &particles,
             Domain<dim> &domain, Fluid<dim> &fluid, ParticleSet<dim> &set,
             Collisions<dim> &collisions, const std::string &model = repulsion,
             const std::string &lubrication = "", const std::string &wall = "",
             const std::string &floor_velocity = "")
  {
    declare_all_parameters(prm);
    prm.parse_input_from_string(
      "set Dimension = " + std::to_string(dim) + "\nset Gravity = " +
      (dim == 2 ? "0, -9.8" : "0, -9.8, 0") + "\nsubsection Geometry\n  set Lower corner = " +
      (dim == 2 ? "0, 0" : "0, 0, 0") + "\n  set Upper corner = " +
      (dim == 2 ? "1, 1.5" : "1, 1.5, 1.2") + "\n  set Subdivisions = " +
      (dim == 2 ? "4, 6" : "4, 6, 5") + "\n  set Periodic directions = " + periodic +
      "\nend\nsubsection Particles\n  set Particles = " + particles +
      "\nend\nsubsection Collisions\n" + model + "end\nsubsection Lubrication\n" +
      lubrication + "end\nsubsection Wall repulsion\n" + wall +
      "end\nsubsection Boundary conditions\n  set Wall velocities = " +
      (floor_velocity.empty() ? "" : "y-: " + floor_velocity) + "\nend\n");
    domain.parse_parameters(prm);
    fluid.parse_parameters(prm);
    set.parse_parameters(prm, domain);
    collisions.parse_parameters(prm);
    collisions.initialize(domain, fluid, set, 0.01);
  }

  template <int dim>
  void test_pair_search(const std::string &periodic)
  {
    std::cout << dim << "D pair search, periodic directions '" << periodic << "'" << std::endl;
    ParameterHandler prm;
    Domain<dim>      domain;
    Fluid<dim>       fluid;
    ParticleSet<dim> set;
    Collisions<dim>  collisions;
    parse(prm, periodic, dim == 2 ? "0.5, 0.5 : 0.1 : 2" : "0.5, 0.5, 0.5 : 0.1 : 2", domain,
          fluid, set, collisions);
    const Point<dim> lower = domain.lower_corner(), upper = domain.upper_corner();

    // Random balls (overlaps allowed: the search does not care), radii 0.01 … 0.06.
    std::mt19937                           random(77 + dim);
    std::uniform_real_distribution<double> uniform(0, 1);
    std::vector<Point<dim>>                x(300);
    std::vector<double>                    r(x.size());
    for (unsigned int k = 0; k < x.size(); ++k)
      {
        for (unsigned int d = 0; d < dim; ++d)
          x[k][d] = lower[d] + uniform(random) * (upper[d] - lower[d]);
        r[k] = 0.01 + 0.05 * uniform(random);
      }
    for (const double reach : {0.0, 0.02, 0.3})
      {
        std::set<std::pair<unsigned int, unsigned int>> expected;
        double largest_error = 0;
        for (unsigned int i = 0; i < x.size(); ++i)
          for (unsigned int j = i + 1; j < x.size(); ++j)
            if (nearest_image_distance(x[i], x[j], domain) - r[i] - r[j] < reach)
              expected.insert({i, j});
        std::set<std::pair<unsigned int, unsigned int>> found;
        for (const auto &p : PairSearch<dim>(domain).pairs(x, r, reach))
          {
            found.insert({p.i, p.j});
            largest_error = std::max(largest_error, std::abs(p.offset.norm() - r[p.i] - r[p.j] - p.gap));
          }
        check(found == expected, "reach " + std::to_string(reach) + ": the " +
                                   std::to_string(expected.size()) + " pairs of the comparison of all pairs",
              std::to_string(found.size()) + " found");
        check(largest_error < 1e-14, "gaps are |offset| - r_i - r_j");
      }
  }

  /// The wall subsection of a test near the floor: the repulsion's range, or the
  /// spring-dashpot with friction.
  const std::string wall_repulsion = "  set Range = 0.05\n";
  const std::string wall_friction  = "  set Range = 0.05\n  set Model = spring-dashpot\n"
                                    "  set Friction coefficient = 0.3\n";

  /// The residual of the particle rows (contacts, lubrication, walls if near_wall), the
  /// particle unknowns (V, ω) it was evaluated at, and the height of particle 0's
  /// end-of-step centre above the floor and of its lowest point below that centre.
  struct ForceRows
  {
    Eigen::VectorXd r, y;
    double          height = 0, depth = 0;
  };

  /// ForceRows of the scene, after checking the rows and their derivative D.
  template <int dim>
  ForceRows test_force(const std::string &periodic, const std::string &particles,
                             const bool in_range, const std::string &model = repulsion,
                             const std::string &lubrication_prm = "", const bool near_wall = false,
                             const std::string &wall_prm = wall_repulsion)
  {
    std::cout << dim << "D contact force, periodic '" << periodic << "', particles " << particles
              << "\n  Collisions: " << model << "  Lubrication: " << lubrication_prm << std::endl;
    ParameterHandler  prm;
    Domain<dim>       domain;
    Fluid<dim>        fluid;
    ParticleSet<dim>  set;
    Collisions<dim>   collisions;
    Lubrication<dim>  lubrication;
    parse(prm, periodic, particles, domain, fluid, set, collisions, model, lubrication_prm,
          near_wall ? wall_prm : "");
    lubrication.parse_parameters(prm);
    lubrication.initialize(domain, fluid, set, 0.01);
    WallRepulsion<dim> walls;
    walls.parse_parameters(prm);
    walls.initialize(domain, fluid, set, 0.01);
    // A BDF2 step of 0.01 with a history, and velocities that turn the pair a little.
    const std::array<double, 3> c{{1.5 / 0.01, -2 / 0.01, 0.5 / 0.01}};
    std::mt19937                           random(5 + dim);
    std::uniform_real_distribution<double> uniform(-0.1, 0.1);
    for (unsigned int k = 0; k < set.size(); ++k)
      {
        set[k].position_old = set[k].position;
        for (unsigned int d = 0; d < dim; ++d)
          set[k].velocity[d] = uniform(random);
        for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
          set[k].omega[RigidBody<dim>::rotation_component(r)] = 10 * uniform(random);
      }
    const unsigned int m  = set.n_unknowns();
    const auto residual = [&](const Eigen::VectorXd &y, Eigen::SparseMatrix<double> *D) {
      set.set_unknowns(y);
      for (unsigned int k = 0; k < set.size(); ++k)
        set[k].contact_force = Tensor<1, dim>();
      Eigen::VectorXd r = Eigen::VectorXd::Zero(m);
      collisions.add_to_particle_rows(set, c, r, D);
      lubrication.add_to_particle_rows(set, c, r, D);
      if (near_wall)
        walls.add_to_particle_rows(set, c, r, D);
      return r;
    };
    const Eigen::VectorXd y0 = set.get_unknowns();
    Eigen::SparseMatrix<double> sparse_D(m, m);
    const Eigen::VectorXd r0 = residual(y0, &sparse_D);
    const Eigen::MatrixXd D  = Eigen::MatrixXd(sparse_D);
    const Tensor<1, dim>  F0 = set[0].contact_force;
    if (!in_range)
      {
        check(r0.norm() == 0 && D.norm() == 0 && F0.norm() == 0,
              "no force and no derivative out of range");
        return {r0, y0, 0, 0};
      }
    check(F0.norm() > 0, "a force in range");
    if (!near_wall)
      check((F0 + set[1].contact_force).norm() <= 1e-14 * F0.norm(), "equal and opposite");
    // A particle that is not round is also turned by a contact off its centre line.
    Tensor<1, dim> e_x, e_y;
    e_x[0] = e_y[1] = 1;
    const bool round = std::abs(set[0].extent(e_x) - set[0].extent(e_y)) < 1e-12;
    if (!round && set[0].first_unknown != numbers::invalid_unsigned_int)
      {
        double torque = 0;
        for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
          torque += std::abs(r0[set[0].first_unknown + dim + r]);
        check(torque > 1e-6 * F0.norm(), "the contact turns the particle that is not round");
      }
    if (set.closure() == AngularVelocityClosure::torque_balance)
      {
        // The contact forces (friction too) neither make nor take angular momentum: about
        // the origin, the torques and the moments of the forces at the end-of-step centres
        // cancel (periodic pairs aside, whose centres are a period apart).
        Tensor<1, 3> angular;
        double       scale = 0;
        for (unsigned int k = 0; k < set.size(); ++k)
          if (const unsigned int u = set[k].first_unknown; u != numbers::invalid_unsigned_int)
            {
              Tensor<1, dim> F;
              Tensor<1, 3>   T;
              for (unsigned int d = 0; d < dim; ++d)
                F[d] = -r0[u + d];
              for (unsigned int r = 0; r < RigidBody<dim>::n_rotations; ++r)
                T[RigidBody<dim>::rotation_component(r)] = -r0[u + dim + r];
              angular += T + RigidBody<dim>::moment(set[k].position_after_step(c), F);
              scale += F.norm() * (set[k].position_after_step(c).norm() + set[k].bounding_radius());
            }
        if (periodic.empty() && !near_wall && set.n_unknowns() == 2 * RigidBody<dim>::n_unknowns)
          check(angular.norm() <= 1e-12 * scale, "the contact keeps the pair's angular momentum",
                "torque sum " + std::to_string(angular.norm()) + " of " + std::to_string(scale));
      }
    Eigen::MatrixXd difference(m, m);
    for (unsigned int j = 0; j < m; ++j)
      {
        Eigen::VectorXd yp = y0, ym = y0;
        yp[j] += fd_step;
        ym[j] -= fd_step;
        difference.col(j) = (residual(yp, nullptr) - residual(ym, nullptr)) / (2 * fd_step);
      }
    check((difference - D).cwiseAbs().maxCoeff() <= fd_tolerance * D.cwiseAbs().maxCoeff(),
          "D is the derivative of the residual in the velocities (central differences)",
          "largest difference " + std::to_string((difference - D).cwiseAbs().maxCoeff()) +
            " of " + std::to_string(D.cwiseAbs().maxCoeff()));
    set.set_unknowns(y0);
    Tensor<1, dim> up;
    up[1] = 1;
    return {r0, y0, set[0].position_after_step(c)[1], set[0].extent(-up)};
  }

  /**
   * Friction on the spring-dashpot contact of the particles (near the floor: with it), as
   * the difference of the rows with and without it: it does no positive work on the
   * particles' motion (force · V + torque · ω ≤ 0 summed over them); with equal semi-axes
   * written as ellipses or ellipsoids (same_as, the scene written with balls) its rows
   * are the balls'.
   */
  template <int dim>
  void test_friction_work(const std::string &particles, const bool near_wall,
                          const std::string &same_as = "")
  {
    const std::string spring = "  set Model = spring-dashpot\n  set Range = 0.05\n";
    const std::string model  = near_wall ? none_model : spring + "  set Friction coefficient = 0.3\n";
    const std::string dry    = near_wall ? none_model : spring;
    const std::string wall_dry = "  set Range = 0.05\n  set Model = spring-dashpot\n";
    const ForceRows with = test_force<dim>("", particles, true, model, "", near_wall, wall_friction);
    const ForceRows without = test_force<dim>("", particles, true, dry, "", near_wall, wall_dry);
    const Eigen::VectorXd friction = without.r - with.r; // the rows are −(force, torque)
    const double          work     = friction.dot(with.y);
    check(friction.norm() > 1e-3 * with.r.norm() && work < 0,
          "friction acts and does negative work", "power " + std::to_string(work));
    if (near_wall)
      {
        // It acts at the middle of the gap between the floor and the particle's lowest
        // point: the torque's part across the force and the floor normal is that lever.
        Tensor<1, dim> F, n;
        Tensor<1, 3>   T;
        n[1] = 1;
        for (unsigned int d = 0; d < dim; ++d)
          F[d] = friction[d];
        for (unsigned int k = 0; k < RigidBody<dim>::n_rotations; ++k)
          T[RigidBody<dim>::rotation_component(k)] = friction[dim + k];
        Tensor<1, 3> n_cross_F;
        if constexpr (dim == 2)
          n_cross_F[2] = n[0] * F[1] - n[1] * F[0];
        else
          n_cross_F = cross_product_3d(n, F);
        const double lever = T * n_cross_F / F.norm_square();
        const double expected = -(with.height + with.depth) / 2;
        check(std::abs(lever - expected) <= 1e-9 * with.depth,
              "friction acts halfway between the floor and the lowest point",
              "lever " + std::to_string(lever) + ", expected " + std::to_string(expected));
      }
    if (!same_as.empty())
      {
        const ForceRows balls = test_force<dim>("", same_as, true, model, "", near_wall, wall_friction);
        check((balls.r - with.r).norm() <= 1e-12 * with.r.norm(),
              "an ellipse of equal semi-axes has the ball's contact rows");
      }
  }

  /// The two disks after a dry bounce, and their mass and moment of inertia.
  struct Bounce
  {
    Tensor<1, 2> V0, V1;
    double       omega0 = 0, omega1 = 0, mass = 0, inertia = 0;
    /// Impulses on disk 1 along the normal of each step and across it, and the pair's
    /// angular momentum about the origin.
    double normal_impulse = 0, tangential_impulse = 0;
    double angular_momentum_before = 0, angular_momentum_after = 0;
    /// Ratio of the relative normal speeds after and before (NaN if they did not part).
    double restitution = std::numeric_limits<double>::quiet_NaN();
  };

  /**
   * Two dry disks of equal mass meet at relative speed 1 along the line of centres (x),
   * with relative tangential speed `tangential` (y), and bounce off with the spring-dashpot
   * force alone: the particle equations m dV/dt = F, J dω/dt = T, integrated with the BDF2
   * formula and Newton's method on the residual and the derivative D that the simulation
   * uses.
   */
  Bounce dry_bounce(const double restitution, const double steps_per_contact,
                    const double friction = 0, const double tangential = 0)
  {
    constexpr int    dim = 2;
    constexpr double stiffness = 1000, density = 2, radius = 0.1, range = 0.01;
    ParameterHandler prm;
    Domain<dim>      domain;
    Fluid<dim>       fluid;
    ParticleSet<dim> set;
    Collisions<dim>  collisions;
    parse(prm, "", "0.37, 0.5 : 0.1 : 2 ; 0.6, 0.5 : 0.1 : 2", domain, fluid, set, collisions,
          "  set Model = spring-dashpot\n  set Range = " + std::to_string(range) +
            "\n  set Spring stiffness = " + std::to_string(stiffness) +
            "\n  set Restitution coefficient = " + std::to_string(restitution) +
            "\n  set Friction coefficient = " + std::to_string(friction) + "\n");
    Bounce result;
    result.mass    = density * Sphere<dim>(radius).volume();
    result.inertia = density * Sphere<dim>(radius).inertia()[2][2];
    const double log_e = std::log(restitution);
    const double t_c   = std::sqrt(result.mass / 2 / stiffness) *
                       std::sqrt(numbers::PI * numbers::PI + log_e * log_e);
    const double dt = t_c / steps_per_contact;
    set[0].velocity = Tensor<1, dim>({0.5, 0.5 * tangential});
    set[1].velocity = -set[0].velocity;
    for (unsigned int k = 0; k < 2; ++k)
      {
        set[k].position_old  = set[k].position - dt * set[k].velocity;
        set[k].velocity_old  = set[k].velocity;
        set[k].velocity_old2 = set[k].velocity;
      }
    const unsigned int n = set.n_unknowns();
    Eigen::VectorXd    mass(n);
    for (unsigned int k = 0; k < 2; ++k)
      for (unsigned int d = 0; d < RigidBody<dim>::n_unknowns; ++d)
        mass[set[k].first_unknown + d] = (d < dim ? result.mass : result.inertia);
    const auto angular_momentum = [&]() {
      double L = 0;
      for (unsigned int k = 0; k < 2; ++k)
        L += result.mass * (set[k].position[0] * set[k].velocity[1] -
                            set[k].position[1] * set[k].velocity[0]) +
             result.inertia * set[k].omega[2];
      return L;
    };
    result.angular_momentum_before = angular_momentum();
    bool touched = false;
    for (unsigned int step = 0; step < 100 * steps_per_contact + 1000; ++step)
      {
        const std::array<double, 3> c{{1.5 / dt, -2 / dt, 0.5 / dt}};
        Eigen::VectorXd             y = set.get_unknowns();
        for (unsigned int it = 0; it < 50; ++it)
          {
            set.set_unknowns(y);
            Eigen::VectorXd r(n);
            for (unsigned int k = 0; k < 2; ++k)
              {
                for (unsigned int d = 0; d < dim; ++d)
                  r[set[k].first_unknown + d] = result.mass * set[k].acceleration(c)[d];
                r[set[k].first_unknown + dim] = result.inertia * set[k].angular_acceleration(c)[2];
              }
            Eigen::SparseMatrix<double> D(mass.size(), mass.size());
            for (int i = 0; i < mass.size(); ++i)
              D.coeffRef(i, i) = mass[i] * c[0];
            for (unsigned int k = 0; k < 2; ++k)
              set[k].contact_force = Tensor<1, dim>();
            collisions.add_to_particle_rows(set, c, r, &D);
            if (r.norm() < 1e-13)
              break;
            y -= Eigen::MatrixXd(D).fullPivLu().solve(r);
          }
        set.set_unknowns(y);
        {
          const Tensor<1, dim> offset = set[0].position_after_step(c) - set[1].position_after_step(c);
          const Tensor<1, dim> n = offset / offset.norm();
          const Tensor<1, dim> F = set[0].contact_force;
          result.normal_impulse += dt * (F * n);
          result.tangential_impulse += dt * (F - (F * n) * n).norm();
        }
        for (unsigned int k = 0; k < 2; ++k)
          {
            const Point<dim> next = set[k].position_after_step(c);
            set[k].position_old   = set[k].position;
            set[k].position       = next;
            set[k].velocity_old2  = set[k].velocity_old;
            set[k].velocity_old   = set[k].velocity;
            set[k].omega_old2     = set[k].omega_old;
            set[k].omega_old      = set[k].omega;
          }
        const double gap = (set[1].position - set[0].position).norm() - 2 * radius;
        touched = touched || gap < range;
        if (touched && gap > range)
          {
            result.V0 = set[0].velocity;
            result.V1 = set[1].velocity;
            result.omega0 = set[0].omega[2];
            result.omega1 = set[1].omega[2];
            result.restitution = set[1].velocity[0] - set[0].velocity[0];
            result.angular_momentum_after = angular_momentum();
            break;
          }
      }
    return result;
  }

  /**
   * An oblique dry bounce with friction 0.1 and tangential speed 1: the surfaces slide
   * throughout (the tangential impulse, 0.1 × the normal one, changes their sliding speed
   * by about 3 × 0.1 × (1 + e) = 0.57 < 1 for disks), so by Coulomb's law the tangential
   * impulse is 0.1 × the normal one, each taken along the normal of its step. The pair's
   * momentum and angular momentum (orbital plus spin) are conserved, and both disks spin
   * the same way.
   */
  void test_friction()
  {
    std::cout << "Oblique dry bounce of two equal disks with friction" << std::endl;
    const double mu = 0.1;
    const Bounce b  = dry_bounce(0.9, 50, mu, 1.0);
    check(std::abs(b.tangential_impulse / b.normal_impulse - mu) < 0.01 * mu,
          "sliding contact: tangential impulse = 0.1 × normal",
          "ratio " + std::to_string(b.tangential_impulse / b.normal_impulse));
    check(std::abs(b.angular_momentum_after - b.angular_momentum_before) <
            1e-3 * b.inertia * std::abs(b.omega0),
          "angular momentum conserved to 1e-3 of a disk's spin (BDF2 conserves it only to O(dt²))",
          std::to_string((b.angular_momentum_after - b.angular_momentum_before) /
                         (b.inertia * b.omega0)) + " of it");
    check(std::abs(b.omega0 - b.omega1) < 1e-9 * std::abs(b.omega0) && b.omega0 != 0,
          "both disks spin the same way, equally");
    // Disk 1 (left) moves up, disk 2 (right) down: friction pushes disk 1 down at its
    // right edge, a clockwise (negative) spin.
    check(b.omega0 < 0, "the sense of the spin", std::to_string(b.omega0));
    check((b.V0 + b.V1).norm() < 1e-12, "momentum conserved");
    const Bounce frictionless = dry_bounce(0.9, 50, 0.0, 1.0);
    check(frictionless.omega0 == 0 &&
            frictionless.tangential_impulse < 1e-12 * frictionless.normal_impulse,
          "without friction no spin and no tangential impulse");
  }

  /// A dry ball after the run of dry_on_floor: its velocity and spin about the axis of
  /// rolling along x (z in 2D, −z in 3D for the right-handed sense), mass, moment of
  /// inertia and gap to the floor, and the largest |F_t|/F_n.
  struct FloorRun
  {
    Tensor<1, 3> V, omega;
    double       mass = 0, inertia = 0, gap = 0, largest_ratio = 0;
    double       restitution = std::numeric_limits<double>::quiet_NaN();
  };

  /**
   * A dry ball (radius 0.1, density 2) starts at (0.5, ...) with velocity V0 just above
   * the floor (which slides along x at floor_velocity), under gravity (0, −9.8) or none,
   * and meets the floor's spring-dashpot wall
   * force (WallRepulsion, range 0.001) and friction: the particle equations
   * m dV/dt = m g + F, J dω/dt = T, integrated for `duration` with BDF2 and Newton's method
   * on the residual and the derivative D that the simulation uses.
   */
  template <int dim>
  FloorRun dry_on_floor(const Tensor<1, dim> &V0, const bool gravity, const double friction,
                        const double restitution, const double duration, const double dt,
                        const double floor_velocity = 0)
  {
    constexpr double radius = 0.1, density = 2, range = 0.001;
    ParameterHandler  prm;
    Domain<dim>       domain;
    Fluid<dim>        fluid;
    ParticleSet<dim>  set;
    Collisions<dim>   collisions;
    WallRepulsion<dim> walls;
    const std::string  centre = (dim == 2 ? "0.5, " : "0.5, ") + std::to_string(radius + range) +
                               (dim == 2 ? "" : ", 0.5");
    parse(prm, "", centre + " : " + std::to_string(radius) + " : " + std::to_string(density),
          domain, fluid, set, collisions, "  set Model = none\n", "",
          "  set Model = spring-dashpot\n  set Range = " + std::to_string(range) +
            "\n  set Restitution coefficient = " + std::to_string(restitution) +
            "\n  set Friction coefficient = " + std::to_string(friction) + "\n",
          floor_velocity == 0 ? "" : std::to_string(floor_velocity) + (dim == 2 ? ", 0" : ", 0, 0"));
    walls.parse_parameters(prm);
    walls.initialize(domain, fluid, set, range);
    FloorRun result;
    result.mass    = density * Sphere<dim>(radius).volume();
    result.inertia = density * Sphere<dim>(radius).inertia()[2][2];
    Particle<dim> &P = set[0];
    P.velocity = P.velocity_old = P.velocity_old2 = V0;
    P.position_old = P.position - dt * V0;
    const Tensor<1, dim> g = (gravity ? fluid.gravity : Tensor<1, dim>());
    const unsigned int   n = set.n_unknowns();
    Eigen::SparseMatrix<double> D_mass(n, n);
    for (unsigned int d = 0; d < n; ++d)
      D_mass.coeffRef(d, d) = (d < dim ? result.mass : result.inertia);
    bool touched = false;
    for (double t = 0; t < duration; t += dt)
      {
        const std::array<double, 3> c{{1.5 / dt, -2 / dt, 0.5 / dt}};
        Eigen::VectorXd             y = set.get_unknowns();
        for (unsigned int it = 0; it < 50; ++it)
          {
            set.set_unknowns(y);
            Eigen::VectorXd r(n);
            for (unsigned int d = 0; d < dim; ++d)
              r[d] = result.mass * (P.acceleration(c)[d] - g[d]);
            for (unsigned int k = 0; k < RigidBody<dim>::n_rotations; ++k)
              r[dim + k] =
                result.inertia * P.angular_acceleration(c)[RigidBody<dim>::rotation_component(k)];
            Eigen::SparseMatrix<double> D = c[0] * D_mass;
            P.contact_force = Tensor<1, dim>();
            walls.add_to_particle_rows(set, c, r, &D);
            if (r.norm() < 1e-13)
              break;
            y -= Eigen::MatrixXd(D).fullPivLu().solve(r);
          }
        set.set_unknowns(y);
        if (P.contact_force[1] > 0)
          result.largest_ratio =
            std::max(result.largest_ratio,
                     std::sqrt(P.contact_force.norm_square() - std::pow(P.contact_force[1], 2)) /
                       P.contact_force[1]);
        const Point<dim> next = P.position_after_step(c);
        P.position_old  = P.position;
        P.position      = next;
        P.velocity_old2 = P.velocity_old;
        P.velocity_old  = P.velocity;
        P.omega_old2    = P.omega_old;
        P.omega_old     = P.omega;
        result.gap      = P.position[1] - radius;
        touched         = touched || result.gap < range;
        if (!gravity && touched && result.gap > range)
          {
            result.restitution = -P.velocity[1] / V0[1];
            break;
          }
      }
    for (unsigned int d = 0; d < dim; ++d)
      result.V[d] = P.velocity[d];
    result.omega = P.omega;
    return result;
  }

  /**
   * A dry ball thrown along the floor at speed 1 with friction 0.3 slides, decelerates at
   * 0.3 g and spins up until its surface stops sliding on the floor; it then rolls at
   * V = V0 m r²/(I + m r²), r = R + g/2 its arm to the contact point in the middle of the
   * gap (2/3 V0 for a disk, 5/7 V0 for a sphere when the gap vanishes). Friction bounds
   * the tangential force by 0.3 times the normal one. A wall contact without gravity
   * bounces with the restitution coefficient.
   */
  template <int dim>
  void test_wall_friction()
  {
    std::cout << dim << "D dry ball thrown along the floor with wall friction" << std::endl;
    const double   mu = 0.3, v0 = 1, dt = 1e-4;
    Tensor<1, dim> V0;
    V0[0]             = v0;
    // Rolling starts after V0/(μ g) (1 + m R²/I)⁻¹ ≈ 0.11 (disk) and 0.10 (sphere).
    const FloorRun run = dry_on_floor<dim>(V0, true, mu, 0.5, 0.3, dt);
    const double   arm = 0.1 + run.gap / 2;
    const double   rolling = v0 * run.mass * arm * arm / (run.inertia + run.mass * arm * arm);
    // Rolling along +x turns the ball clockwise about z.
    check(std::abs(run.V[0] - rolling) < 2e-3 * v0,
          "the ball ends rolling at V0 m r²/(I + m r²) = " + std::to_string(rolling),
          "V = " + std::to_string(run.V[0]));
    check(std::abs(run.V[0] + run.omega[2] * arm) < 2e-3 * v0,
          "its surface does not slide on the floor: V = -ω r",
          "V + ω r = " + std::to_string(run.V[0] + run.omega[2] * arm));
    check(run.largest_ratio <= mu * (1 + 1e-9), "|F_t| <= 0.3 F_n at every step",
          "largest ratio " + std::to_string(run.largest_ratio));
    check(std::abs(run.V[1]) < 1e-6 && std::abs(run.gap - 0.001) < 0.001,
          "the ball stays on the floor, within the range",
          "V_y = " + std::to_string(run.V[1]) + ", gap " + std::to_string(run.gap));
    // A ball at rest on a floor sliding at 1 is dragged until its surface moves with the
    // floor: V + |ω| r = 1 with V = I/(I + m r²) (1/3 for a disk, 2/7 for a sphere).
    const FloorRun dragged = dry_on_floor<dim>(Tensor<1, dim>(), true, mu, 0.5, 0.3, dt, v0);
    const double   dragged_arm = 0.1 + dragged.gap / 2;
    const double   carried =
      v0 * dragged.inertia / (dragged.inertia + dragged.mass * dragged_arm * dragged_arm);
    check(std::abs(dragged.V[0] - carried) < 2e-3 * v0 &&
            std::abs(dragged.V[0] + dragged.omega[2] * dragged_arm - v0) < 2e-3 * v0,
          "a sliding floor drags the ball to V = I/(I + m r²) = " + std::to_string(carried) +
            ", rolling on the floor",
          "V = " + std::to_string(dragged.V[0]) + ", surface " +
            std::to_string(dragged.V[0] + dragged.omega[2] * dragged_arm));
    const FloorRun frictionless = dry_on_floor<dim>(V0, true, 0, 0.5, 0.3, dt);
    check(std::abs(frictionless.V[0] - v0) < 1e-9 && frictionless.omega.norm() == 0,
          "without friction it slides on, unspun");
    Tensor<1, dim> down;
    down[1] = -0.5;
    // The dry contact lasts t_c = √(m/k) √(π² + ln² e) ≈ 3·10⁻³ (k = 100 m g / ρ): 30 steps.
    const double e = 0.6, bounced = dry_on_floor<dim>(down, false, 0, e, 0.1, dt).restitution;
    check(std::abs(bounced - e) < 0.02, "a ball hitting the wall bounces with e = 0.6",
          "measured " + std::to_string(bounced));
  }

  void test_restitution()
  {
    std::cout << "Dry bounce of two equal disks with the spring-dashpot force" << std::endl;
    // The dashpot's damping must give the restitution coefficient once the contact is
    // resolved in time; BDF2 then adds an error of O((dt/t_c)²).
    for (const double e : {0.3, 0.7, 0.95})
      {
        const double measured = dry_bounce(e, 50).restitution;
        check(std::abs(measured - e) < 0.01, "restitution " + std::to_string(e) +
                                                 " with 50 steps per contact",
              "measured " + std::to_string(measured));
      }
    // With few steps per contact the implicit time integration takes energy as well: the
    // trade that the log line of Collisions::describe warns about.
    std::cout << "  steps per contact : measured restitution for e = 0.9" << std::endl;
    for (const double steps : {1.0, 3.0, 10.0, 20.0, 50.0})
      std::cout << "    " << steps << " : " << dry_bounce(0.9, steps).restitution << std::endl;
    const double coarse = dry_bounce(0.9, 3).restitution, fine = dry_bounce(0.9, 50).restitution;
    check(coarse < fine, "fewer steps per contact bounce less",
          std::to_string(coarse) + " with 3 steps, " + std::to_string(fine) + " with 50");
  }

} // namespace

namespace
{
  /// The contact geometry of ellipses and ellipsoids (ContactGeometry) against their
  /// surfaces sampled densely: the gap between two of them, turned at random, is the
  /// smallest distance between the samples (to the sampling's resolution), the contact
  /// points lie on the surfaces, gap·n apart; an overlapping pair has a negative gap; the
  /// gap to a wall is the smallest distance of the samples from it.
  template <int dim>
  void test_contact_geometry()
  {
    std::cout << dim << "D contact geometry of ellipsoids" << std::endl;
    std::mt19937                           random(11 + dim);
    std::uniform_real_distribution<double> uniform(-1, 1);
    const auto make = [&](const Point<dim> &X, const Tensor<1, dim> &a) {
      Particle<dim> p;
      p.shape = std::make_shared<const Ellipsoid<dim>>(a, "test");
      Eigen::Vector3d axis(dim == 3 ? uniform(random) : 0, dim == 3 ? uniform(random) : 0, 1);
      p.place(X, Eigen::Quaterniond(Eigen::AngleAxisd(3 * uniform(random), axis.normalized())));
      return p;
    };
    // Surface samples: the unit circle or sphere mapped by Q diag(a).
    const auto samples = [&](const Particle<dim> &p, const Tensor<1, dim> &a) {
      std::vector<Point<dim>> x;
      const unsigned int      n = (dim == 2 ? 4000 : 60);
      for (unsigned int s = 0; s < n; ++s)
        for (unsigned int t = 0; t < (dim == 2 ? 1u : 2 * n); ++t)
          {
            const double   phi = 2 * numbers::PI * (dim == 2 ? s : t) / (dim == 2 ? n : 2 * n);
            const double   theta = numbers::PI * (s + 0.5) / n;
            Tensor<1, dim> u;
            u[0] = a[0] * std::cos(phi) * (dim == 3 ? std::sin(theta) : 1.0);
            u[1] = a[1] * std::sin(phi) * (dim == 3 ? std::sin(theta) : 1.0);
            if (dim == 3)
              u[dim - 1] = a[dim - 1] * std::cos(theta);
            x.push_back(p.geometry_center + p.geometry_rotation * u);
          }
      return x;
    };
    unsigned int n_pairs = 0, wrong_gap = 0, wrong_points = 0, wrong_wall = 0;
    double       worst = 0;
    for (unsigned int trial = 0; trial < 12; ++trial)
      {
        Tensor<1, dim> a, b;
        for (unsigned int d = 0; d < dim; ++d)
          {
            a[d] = 0.2 + 0.1 * uniform(random);
            b[d] = 0.15 + 0.05 * uniform(random);
          }
        Tensor<1, dim> direction;
        for (unsigned int d = 0; d < dim; ++d)
          direction[d] = uniform(random);
        direction /= direction.norm();
        const double    reach = (trial < 10 ? 0.45 + 0.05 * uniform(random) : 0.1);
        const Particle<dim> A = make(Point<dim>() + reach * direction, a), B = make(Point<dim>(), b);
        const auto          c = ContactGeometry<dim>::pair(A, B, reach * direction);
        const auto   xa = samples(A, a), xb = samples(B, b);
        // The smallest distance of the samples, over all pairs: raw arrays, as a Debug
        // build checks every index of a Point or a container.
        std::vector<double> qb_storage(dim * xb.size());
        for (unsigned int j = 0; j < xb.size(); ++j)
          for (unsigned int d = 0; d < dim; ++d)
            qb_storage[dim * j + d] = xb[j][d];
        const double *     qb = qb_storage.data();
        const unsigned int nb = xb.size();
        double             sampled_square = 1e300;
        for (const auto &p : xa)
          {
            double pa[dim];
            for (unsigned int d = 0; d < dim; ++d)
              pa[d] = p[d];
            for (unsigned int j = 0; j < nb; ++j)
              {
                double square = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const double e = pa[d] - qb[dim * j + d];
                    square += e * e;
                  }
                if (square < sampled_square)
                  sampled_square = square;
              }
          }
        const double sampled = std::sqrt(sampled_square);
        if (trial >= 10) // deep overlap: centres 0.1 apart
          {
            wrong_gap += !(c.gap < 0);
            continue;
          }
        if (sampled < 0.02) // the sampling cannot tell a touching pair from an overlap
          continue;
        ++n_pairs;
        // The samples are a subset of the surfaces: the true gap is at most their distance,
        // and below it by no more than the sampling's chord error.
        const double resolution = (dim == 2 ? 1e-6 : 1e-3);
        worst = std::max(worst, sampled - c.gap);
        wrong_gap += !(c.gap <= sampled + 1e-12 && c.gap >= sampled - resolution);
        const Point<dim> pa = A.geometry_center + c.arm_i, pb = B.geometry_center + c.arm_j;
        const auto       on_surface = [](const Particle<dim> &p, const Point<dim> &x) {
          return std::abs(p.shape->surface_distance(p.body_offset(x))) < 1e-9;
        };
        wrong_points += !(on_surface(A, pa) && on_surface(B, pb) &&
                          (pa - pb - c.gap * c.normal).norm() < 1e-8);
        // A wall below B (inward normal e_y) at 0.05 from B's lowest sample.
        Tensor<1, dim> up;
        up[1] = 1;
        double lowest = 1e300;
        for (const auto &q : xb)
          lowest = std::min(lowest, q[1]);
        const double floor = lowest - 0.05;
        const auto   w = ContactGeometry<dim>::wall(B, up, -floor - B.bounding_radius());
        wrong_wall += !(std::abs(w.gap - 0.05) < resolution &&
                        on_surface(B, B.geometry_center + w.arm_i));
      }
    check(n_pairs >= 6, std::to_string(n_pairs) + " separated pairs compared");
    check(wrong_gap == 0, "the gap is the sampled surfaces' distance; negative when overlapping",
          "largest sampled − gap " + sci(worst));
    check(wrong_points == 0, "the contact points lie on the surfaces, gap · n apart");
    check(wrong_wall == 0, "the gap to a wall is the lowest sample's");
  }
} // namespace

int main()
{
  try
    {
      test_pair_search<2>("");
      test_pair_search<2>("x, y");
      test_pair_search<3>("x, z");
      // A pair 0.03 apart (range 0.05), off the line of the axes; the same across the
      // periodic boundary in x; a pair 0.1 apart (out of range).
      test_force<2>("", "0.4, 0.5 : 0.1 : 2 ; 0.6, 0.62 : 0.12 : 3", true);
      test_force<2>("x", "0.11, 0.5 : 0.1 : 2 ; 0.88, 0.55 : 0.1 : 3", true);
      test_force<2>("", "0.3, 0.5 : 0.1 : 2 ; 0.6, 0.5 : 0.1 : 3", false);
      test_force<3>("", "0.4, 0.5, 0.5 : 0.1 : 2 ; 0.6, 0.62, 0.55 : 0.12 : 3", true);
      test_force<3>("y", "0.5, 0.11, 0.5 : 0.1 : 2 ; 0.52, 1.38, 0.51 : 0.1 : 3", true);
      // The spring-dashpot 0.006 into its range 0.05, the second ball fixed in 3D; and 0.06
      // apart (out of range).
      const std::string spring = "  set Model = spring-dashpot\n  set Range = 0.05\n";
      test_force<2>("", "0.4, 0.5 : 0.1 : 2 ; 0.59, 0.6 : 0.1 : 3", true, spring);
      test_force<3>("", "0.4, 0.5, 0.5 : 0.1 : 2 ; 0.59, 0.6, 0.5 : 0.1 : 3 : fixed", true,
                    spring);
      test_force<2>("", "0.4, 0.5 : 0.1 : 2 ; 0.66, 0.5 : 0.1 : 3", false, spring);
      test_restitution();
      test_friction();
      test_wall_friction<2>();
      test_wall_friction<3>();
      // Friction on a sliding, turning pair, in 2D and 3D.
      const std::string friction = spring + "  set Friction coefficient = 0.3\n";
      test_force<2>("", "0.4, 0.5 : 0.1 : 2 ; 0.59, 0.6 : 0.1 : 3", true, friction);
      test_force<3>("", "0.4, 0.5, 0.5 : 0.1 : 2 ; 0.59, 0.6, 0.5 : 0.1 : 3", true, friction);
      // The lubrication correction alone (resolved gap 0.05): a pair 0.03 apart, turning;
      // a ball 0.02 off the floor with a fixed one 0.03 away (pair and wall at once); 0.06
      // apart (out of range).
      const std::string none = "  set Model = none\n";
      const std::string lubrication = "  set Enabled = true\n  set Resolved gap = 0.05\n";
      test_force<2>("", "0.4, 0.5 : 0.1 : 2 ; 0.6, 0.62 : 0.12 : 3", true, none, lubrication);
      test_force<3>("", "0.4, 0.5, 0.5 : 0.1 : 2 ; 0.6, 0.62, 0.55 : 0.12 : 3", true, none,
                    lubrication);
      test_force<3>("", "0.4, 0.12, 0.5 : 0.1 : 2 ; 0.63, 0.12, 0.5 : 0.1 : 3 : fixed", true,
                    none, lubrication, true);
      test_force<2>("", "0.4, 0.5 : 0.1 : 2 ; 0.66, 0.5 : 0.1 : 3", false, none, lubrication);
      // Ellipses and ellipsoids: their true gap, the torque of a contact off the line of
      // centres; a pair in range, the repulsion and the spring-dashpot, and one near the
      // floor.
      test_contact_geometry<2>();
      test_contact_geometry<3>();
      test_force<2>("", "0.4, 0.5 : ellipse 0.15, 0.08, 30 : 2 ; 0.62, 0.6 : ellipse 0.1, 0.06, -20 : 3",
                    true);
      test_force<2>("", "0.4, 0.5 : ellipse 0.15, 0.08, 30 : 2 ; 0.62, 0.6 : ellipse 0.1, 0.06, -20 : 3",
                    true, spring);
      test_force<3>("", "0.4, 0.5, 0.5 : ellipsoid 0.15, 0.08, 0.1, 1, 2, 3, 30 : 2 ; "
                    "0.62, 0.62, 0.52 : ellipsoid 0.1, 0.06, 0.09, 1, 0, 0, 50 : 3", true, spring);
      test_force<2>("", "0.4, 0.12 : ellipse 0.15, 0.08, 30 : 2", true, none, "", true);
      test_force<3>("", "0.4, 0.12, 0.5 : ellipsoid 0.15, 0.08, 0.1, 1, 2, 3, 30 : 2", true,
                    spring, "", true);
      // Friction on ellipses and ellipsoids, between a pair and with the floor; of equal
      // semi-axes, against the balls.
      test_friction_work<2>("0.4, 0.5 : ellipse 0.15, 0.08, 30 : 2 ; 0.62, 0.6 : ellipse 0.1, 0.06, -20 : 3",
                            false);
      test_friction_work<2>("0.4, 0.5 : ellipse 0.1, 0.1, 40 : 2 ; 0.59, 0.6 : ellipse 0.1, 0.1, -20 : 3",
                            false, "0.4, 0.5 : 0.1 : 2 ; 0.59, 0.6 : 0.1 : 3");
      test_friction_work<3>("0.4, 0.5, 0.5 : ellipsoid 0.15, 0.08, 0.1, 1, 2, 3, 30 : 2 ; "
                            "0.62, 0.62, 0.52 : ellipsoid 0.1, 0.06, 0.09, 1, 0, 0, 50 : 3", false);
      test_friction_work<3>("0.4, 0.5, 0.5 : ellipsoid 0.1, 0.1, 0.1, 1, 2, 3, 30 : 2 ; "
                            "0.59, 0.6, 0.5 : ellipsoid 0.1, 0.1, 0.1, 1, 0, 0, 50 : 3", false,
                            "0.4, 0.5, 0.5 : 0.1 : 2 ; 0.59, 0.6, 0.5 : 0.1 : 3");
      test_friction_work<2>("0.4, 0.12 : ellipse 0.15, 0.08, 30 : 2", true);
      test_friction_work<2>("0.4, 0.12 : ellipse 0.1, 0.1, 30 : 2", true, "0.4, 0.12 : 0.1 : 2");
      test_friction_work<3>("0.4, 0.12, 0.5 : ellipsoid 0.15, 0.08, 0.1, 1, 2, 3, 30 : 2", true);
      test_friction_work<3>("0.4, 0.12, 0.5 : ellipsoid 0.1, 0.1, 0.1, 1, 2, 3, 30 : 2", true,
                            "0.4, 0.12, 0.5 : 0.1 : 2");
    }
  catch (const std::exception &exc)
    {
      std::cerr << "Unexpected exception: " << exc.what() << std::endl;
      return 2;
    }
  return unit_check::summary();
}
