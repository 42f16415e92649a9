#ifndef fdparticle_particles_particle_set_h
#define fdparticle_particles_particle_set_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <fdparticle/base/box.h>
#include <fdparticle/base/statistics_table.h>
#include <fdparticle/particles/cell_list.h>
#include <fdparticle/particles/rigid_body.h>
#include <fdparticle/particles/shape.h>
#include <fdparticle/base/time_stepper.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <optional>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /// How a particle moves: by its force and torque balance, not at all, or with a given
  /// constant velocity and angular velocity. Only free particles have particle equations;
  /// the force and torque of all are reported.
  enum class ParticleMotion
  {
    free,
    fixed,
    prescribed
  };

  /// Closure for the angular velocity (doc/method.md §10, §11 item 1).
  enum class AngularVelocityClosure
  {
    torque_balance, ///< (F5): (ρ_k − ρ_f) J dω/dt + <λ, θ × r> = 0 (default)
    kinematic       ///< seed 3.14d: |P| ω = ½ ∫_P ∇ × u
  };

  /// One rigid particle: its shape, motion and time history.
  template <int dim>
  struct Particle
  {
    unsigned int   id = 0;
    ParticleMotion motion = ParticleMotion::free;
    double         density = 0;
    /// The geometry about the centre (shared by copies of the particle; never changed).
    std::shared_ptr<const Shape<dim>> shape;

    /// X^n and X^{n−1}; geometry_center is where the ball sits during the current step.
    Point<dim> position, position_old, geometry_center;
    /// The orientation during the current step (predicted as geometry_center is) and its
    /// rotation matrix Q, body to world: what the geometry of a shape that is not
    /// isotropic is turned by (place()).
    Eigen::Quaterniond geometry_orientation = Eigen::Quaterniond::Identity();
    Tensor<2, dim>     geometry_rotation = unit_symmetric_tensor<dim>();
    /// V and ω: current iterate (t^{n+1} during a step) and the two previous levels.
    Tensor<1, dim> velocity, velocity_old, velocity_old2;
    Tensor<1, 3>   omega, omega_old, omega_old2;
    /// q^n and q^{n−1}: the orientation at the last two time levels.
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    Eigen::Quaterniond orientation_old = Eigen::Quaterniond::Identity();
    /// δ^n: the rotation vector (angle times axis) that turned q^{n−1} into q^n.
    Tensor<1, 3> last_rotation() const
    {
      return RigidBody<dim>::rotation_vector(orientation * orientation_old.inverse());
    }

    /// Hydrodynamic force (buoyancy included) and torque of the last step.
    Tensor<1, dim> force;
    Tensor<1, 3>   torque;
    /// Contact force of the last step (WallRepulsion and Collisions), not part of 'force'.
    Tensor<1, dim> contact_force;

    /// Offset of (V, ω) in the particle block; numbers::invalid_unsigned_int if not free.
    unsigned int first_unknown = numbers::invalid_unsigned_int;

    /// X^{n+1} from the BDF formula for dX/dt = V with coefficients c (Euler for BDF1).
    Point<dim> position_after_step(const std::array<double, 3> &c) const
    {
      return Point<dim>((velocity - c[1] * position - c[2] * position_old) / c[0]);
    }

    /// dV/dt and dω/dt at the end of the step by the BDF formula with coefficients c
    /// (doc/method.md §2), at the current iterate of V and ω.
    Tensor<1, dim> acceleration(const std::array<double, 3> &c) const
    {
      return c[0] * velocity + c[1] * velocity_old + c[2] * velocity_old2;
    }
    Tensor<1, 3> angular_acceleration(const std::array<double, 3> &c) const
    {
      return c[0] * omega + c[1] * omega_old + c[2] * omega_old2;
    }
    /// Put the particle's geometry at X turned by q for the coming step.
    void place(const Point<dim> &X, const Eigen::Quaterniond &q)
    {
      geometry_center = X;
      geometry_orientation = q;
      geometry_rotation = RigidBody<dim>::rotation_matrix(q);
    }

    double volume() const { return shape->volume(); }
    /// J/ρ in the world frame during the step: Q J_body Qᵀ (3 × 3; 2D uses zz).
    Tensor<2, 3> inertia() const
    {
      if (shape->is_isotropic())
        return shape->inertia();
      const Tensor<2, 3> Q = RigidBody<dim>::template rotation_matrix<3>(geometry_orientation);
      return Q * shape->inertia() * transpose(Q);
    }
    /// Whether d(Jω)/dt is J dω/dt with one number J: for a ball, and in 2D, where the
    /// particle turns about z only and J_zz stays.
    bool constant_inertia() const { return dim == 2 || shape->is_isotropic(); }
    /// ρ d(Jω)/dt at the end of the step by the BDF formula with coefficients c, at the
    /// current iterate of ω (doc/method.md §0 (F5), §13): ρ J_zz dω/dt with constant
    /// inertia, else ρ (J dω/dt + ω × Jω) with J = Q J_body Qᵀ. What the torque balance
    /// takes with ρ = ρ_k − ρ_f and the reported torque with ρ = ρ_f (§9).
    Tensor<1, 3> angular_momentum_rate(const std::array<double, 3> &c, const double rho) const
    {
      const Tensor<2, 3> J = inertia();
      const Tensor<1, 3> dwdt = angular_acceleration(c);
      if (constant_inertia())
        return rho * J[2][2] * dwdt;
      return rho * (J * dwdt + cross_product_3d(omega, J * omega));
    }
    /// The derivative of angular_momentum_rate() by ω: ρ J_zz c0 on the diagonal with
    /// constant inertia, else ρ (c0 J + [ω]× J − [Jω]×), column m the derivative by ω_m.
    Tensor<2, 3> angular_momentum_rate_derivative(const std::array<double, 3> &c,
                                                  const double rho) const
    {
      const Tensor<2, 3> J = inertia();
      Tensor<2, 3>       D;
      if (constant_inertia())
        {
          for (unsigned int i = 0; i < 3; ++i)
            D[i][i] = rho * J[2][2] * c[0];
          return D;
        }
      const Tensor<1, 3> Jw = J * omega;
      for (unsigned int m = 0; m < 3; ++m)
        {
          Tensor<1, 3> em;
          em[m] = 1;
          const Tensor<1, 3> column =
            c[0] * (J * em) + cross_product_3d(omega, J * em) - cross_product_3d(Jw, em);
          for (unsigned int i = 0; i < 3; ++i)
            D[i][m] = rho * column[i];
        }
      return D;
    }
    /// The radius of the ball about the centre that holds the particle: what bins, walls
    /// and the contact models see (Shape::bounding_radius).
    double bounding_radius() const { return shape->bounding_radius(); }
    static constexpr double surface_tolerance = Shape<dim>::surface_tolerance;

    /// The box's length in each periodic direction, 0 in the others. A ball that crosses
    /// a periodic face is also at its images X + Σ_d k_d period_d e_d (k_d integers): the
    /// geometric questions below are answered for all of them (doc/method.md §12).
    Tensor<1, dim> period;

    /// x − X to the nearest image of the centre: the arm of a point of the ball.
    Tensor<1, dim> offset(const Point<dim> &x) const
    {
      return Box<dim>::nearest_image(x - geometry_center, period);
    }

    /// Whether x is in the particle, its surface included (within surface_tolerance).
    /// The nearest image is the only one that can contain x (a particle is narrower
    /// than a period).
    bool contains(const Point<dim> &x) const { return shape->contains(body_offset(x)); }
    /// The point of the particle farthest along the world direction n (|n| = 1), as an
    /// offset from the centre, turned as during the step (Shape::support_point).
    Tensor<1, dim> support_point(const Tensor<1, dim> &n) const
    {
      return shape->is_isotropic() ?
               shape->support_point(n) :
               geometry_rotation * shape->support_point(transpose(geometry_rotation) * n);
    }
    /// How far the particle reaches from its centre along n: n · support_point(n).
    double extent(const Tensor<1, dim> &n) const
    {
      return shape->is_isotropic() ? bounding_radius() : n * support_point(n);
    }

    /// offset(x) in the body frame, Qᵀ (x − X) (unturned for an isotropic shape): what
    /// Shape's questions take.
    Tensor<1, dim> body_offset(const Point<dim> &x) const
    {
      const Tensor<1, dim> r = offset(x);
      return shape->is_isotropic() ? r : transpose(geometry_rotation) * r;
    }
    /// Whether the particle overlaps the box by more than touching (within
    /// surface_tolerance): its bounding ball does, and so does the shape.
    bool meets(const BoundingBox<dim> &box) const
    {
      const Point<dim> X = centre_nearest(box);
      return distance(box, X) < bounding_radius() * (1 - surface_tolerance) &&
             (shape->is_isotropic() || shape->meets(box, X, geometry_rotation));
    }
    /// Distance from the nearest image of the centre to the nearest point of box (0 if
    /// the centre is inside).
    double distance_to(const BoundingBox<dim> &box) const
    {
      return distance(box, centre_nearest(box));
    }
    /// The image of the centre nearest to the box.
    Point<dim> centre_nearest(const BoundingBox<dim> &box) const
    {
      // The image nearest to the box's middle is, direction by direction, the nearest to
      // the box: the gap to an interval grows with the distance to its middle.
      Point<dim> X = geometry_center;
      for (unsigned int d = 0; d < dim; ++d)
        if (period[d] > 0)
          X[d] += period[d] *
                  std::round((0.5 * (box.lower_bound(d) + box.upper_bound(d)) - X[d]) / period[d]);
      return X;
    }
    /// The images of the centre closer than reach to the box: one unless the ball crosses
    /// a periodic face and the box reaches both sides of the period.
    std::vector<Point<dim>> centres_near(const BoundingBox<dim> &box, const double reach) const;

  private:
    /// Distance from x to the nearest point of box (0 if x is inside).
    static double distance(const BoundingBox<dim> &box, const Point<dim> &x)
    {
      double d2 = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double e = std::max({box.lower_bound(d) - x[d], 0.0, x[d] - box.upper_bound(d)});
          d2 += e * e;
        }
      return std::sqrt(d2);
    }
  };

  /// Set p's shape and orientation from the shape field of an entry: a radius (a ball),
  /// 'ellipse a, b [, angle]' (2D; the a axis turned by angle degrees from x) or
  /// 'ellipsoid a, b, c [, axis x, y, z, angle]' (3D; the body turned by angle degrees
  /// about the axis); the numbers may be separated by spaces instead of commas (a column of
  /// a particle file). Throws a one-line error naming `name` for a bad field.
  template <int dim>
  void read_shape(const std::string &field, const std::string &name, Particle<dim> &p);

  /**
   * The particles of a scene (subsection Particles): parsing and validation of the list,
   * their unknowns' numbering in the particle block, and the kinematics advanced after
   * each step ((F6) of doc/method.md §0, with the BDF formula of the scheme for X, §2).
   */
  template <int dim>
  class ParticleSet
  {
  public:
    static void declare_parameters(ParameterHandler &prm);

    /**
     * The smallest radius accepted, in units of the finest cell edge (refused in
     * Simulation, which knows the mesh). A smaller ball fills under 1/1000 of a cell in
     * 3D: the cut cells' Gauss points may all miss it (singular particle block), the
     * multiplier cannot tell it from its cell, and the level-set rule recurses
     * log2(h / R) levels deep. Scenes warn below R = h/2 already (d/h < 2); the
     * smallest ball of the shipped scenes has R = 0.8 h.
     */
    static constexpr double min_radius_in_cells = 0.1;

    /// Reads the particles (the Particles list, then the Particle file, then the Random
    /// particles) and checks them against the box: inside, off the walls, no overlaps.
    /// The file is read on rank 0 of comm and broadcast.
    void parse_parameters(ParameterHandler &prm, const Box<dim> &domain,
                          const MPI_Comm comm = MPI_COMM_SELF);

    unsigned int              size() const { return particles.size(); }
    Particle<dim> &           operator[](const unsigned int k) { return particles[k]; }
    const Particle<dim> &     operator[](const unsigned int k) const { return particles[k]; }
    AngularVelocityClosure    closure() const { return angular_closure; }

    /// Size of the particle block: dim + n_rotations per free particle.
    unsigned int n_unknowns() const { return n_block_unknowns; }

    /// Mean velocity of the free particles, as three components (0 if there are none).
    Tensor<1, 3> mean_free_velocity() const;
    /// statistics.csv's mean_particle_vx, _vy, _vz: mean_free_velocity().
    void declare_columns(StatisticsTable &statistics) const;
    void statistics(StatisticsTable &statistics) const;

    /// Index of the particle containing x during this step, or -1 (fluid); the lowest
    /// index if two contain it. O(1) per point: only the balls of x's bins are tried.
    int locate(const Point<dim> &x) const;

    /// The balls that meet the box during this step, in increasing order. O(1) per box
    /// of the size of a ball: only the balls of the bins the box reaches are tried.
    std::vector<unsigned int> meeting(const BoundingBox<dim> &box) const;

    /// Put each ball at its (extrapolated) position for the coming step.
    void prepare_step(const TimeStepper &time);
    /// Start the free particles' (V, ω) of the coming step from their values at the last
    /// two steps, extrapolated as the position (Newton's initial guess, doc/method.md §5).
    void extrapolate_velocities(const TimeStepper &time);
    /// Copy the particle block into (V, ω) of the free particles, and back.
    void set_unknowns(const Eigen::VectorXd &y);
    Eigen::VectorXd get_unknowns() const;
    /// Accept the step: move the balls with the BDF formula (a centre that leaves the box
    /// through a periodic face enters on the other side), rotate, shift the history.
    void finish_step(const TimeStepper &time);

    /**
     * Throw a one-sentence error if a ball touches a wall, is wider than a periodic
     * direction or overlaps another ball (found by PairSearch, O(N)): the fictitious-domain method
     * cannot represent overlapping balls, and past that point the results would be
     * meaningless. The repulsion forces (WallRepulsion, Collisions) keep the balls apart;
     * this is the stop when they are off or too weak. Called after each step (the time
     * loop then retries with a smaller step) and by parse_parameters.
     */
    void check_positions(const Box<dim> &domain, const double time) const;

    /// A number that changes whenever the balls' geometry may have changed (their index is
    /// rebuilt), unique over every particle set of the run (a copy keeps it): what is
    /// computed from the geometry, such as the cut cells' rules, stays valid while it is
    /// the same.
    std::uint64_t geometry_revision() const { return revision; }

    /// The state of every particle (positions, velocity histories, orientation, forces)
    /// as exact text, for checkpoints; load() expects the same particles.
    void save(std::ostream &out) const;
    void load(std::istream &in);

  private:
    std::vector<Particle<dim>> particles;
    Box<dim>                domain;
    /**
     * The balls' geometry centres in bins at least 2 R_max wide, rebuilt whenever the
     * centres move (update_index): the cell-to-particles lookups of the per-cell and
     * per-point loops (locate, meeting) then cost O(1) instead of O(N) each.
     */
    std::optional<CellList<dim>> index;
    /// See geometry_revision().
    std::uint64_t revision = 0;
    /// The centres the index was built with, to assert that it is current.
    std::vector<Point<dim>> indexed_centres;
    double                  largest_radius = 0;
    void                    update_index();
    /// Move the ball's centre (and its history) by whole periods into [lower, upper).
    void                    wrap(Particle<dim> &p) const;
    bool                    index_is_current() const;
    AngularVelocityClosure     angular_closure = AngularVelocityClosure::torque_balance;
    unsigned int               n_block_unknowns = 0;
  };
} // namespace fdparticle

#endif
