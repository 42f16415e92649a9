#ifndef fdparticle_particles_contact_friction_h
#define fdparticle_particles_contact_friction_h

#include <deal.II/base/tensor.h>

#include <fdparticle/base/box.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/particles/spring_dashpot_law.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <array>
#include <functional>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Coulomb friction at the contact point of two particles, or of a particle and a wall
   * (doc/method.md §12): a tangential force opposing the sliding velocity there,
   *
   *   F_t,i = −μ_c F_n v_t / √(|v_t|² + v_s²) = −F_t,j,
   *   v_t = tangential part of V_i + ω_i × r_i − V_j − ω_j × r_j,
   *
   * and the torques r_i × F_t,i and r_j × F_t,j. The contact point is the middle of the
   * gap g between the surfaces' nearest points (ContactGeometry: for balls on the line of
   * centres), r_i = s_i − (g/2) n and r_j = s_j + (g/2) n with s the arms to those
   * points: the contact acts across a gap (or an overlap), and one point for both keeps
   * the pair's angular momentum. Against a wall, the partner is the wall: at rest or
   * sliding along itself, of infinite mass. The Coulomb law's jump at v_t = 0 is smoothed
   * over the slip velocity v_s, so the force has a derivative for Newton; a contact that
   * should stick creeps at a speed of order v_s instead.
   *
   * It is implicit like the normal force, evaluated at X^{n+1}(V), V and ω of the
   * iterate. Its block of the particle matrix, at most 12 × 12 per contact, is taken by
   * central differences of this force in the two particles' unknowns: its exact
   * derivative (through the normal force, the turning normal and the smoothed direction)
   * is long, and a contact's block is small.
   */
  template <int dim>
  class ContactFriction
  {
  public:
    /// The normal force magnitude at gap g and normal relative velocity v_n.
    using NormalForce = std::function<double(const double gap, const double normal_velocity)>;

    /// Friction of the given coefficient on a contact whose normal force is the spring:
    /// the slip velocity is slip_velocity_fraction × (its range / its duration).
    ContactFriction(const double coefficient, const SpringDashpotLaw &spring);

    /**
     * Add the friction of particles i and j, whose centres at the iterate are offset by
     * X_i − X_j + shift (shift: the periodic image), to the force and torque rows of the
     * free ones, its derivative to D (if given), and the force to contact_force.
     */
    void add_pair(ParticleSet<dim> &particles, const unsigned int i, const unsigned int j,
                  const Tensor<1, dim> &shift, const NormalForce &normal_force,
                  const std::array<double, 3> &c, Eigen::VectorXd &r_p,
                  Eigen::SparseMatrix<double> *D) const;

    /// The same for particle i against a wall, wall.gap from its bounding ball at the iterate.
    void add_wall(ParticleSet<dim> &particles, const unsigned int i,
                  const typename Box<dim>::WallGap &wall, const NormalForce &normal_force,
                  const std::array<double, 3> &c, Eigen::VectorXd &r_p,
                  Eigen::SparseMatrix<double> *D) const;

  private:
    /// The slip velocity, relative to the spring's velocity scale ρ/t_c (it crosses its
    /// range in about t_c): a contact that should stick creeps at a thousandth of the speed
    /// that would close the range within one contact time.
    static constexpr double slip_velocity_fraction = 1e-3;

    static constexpr unsigned int n_unknowns = RigidBody<dim>::n_unknowns;
    /// The unknowns (V then ω) of particle i, then of j, or their force and torque rows.
    using PairVector = Eigen::Matrix<double, 2 * n_unknowns, 1>;
    /// The step of the central differences, relative to the slip velocity (the shortest
    /// scale on which the force changes): truncation of order (10⁻⁴)² relative, and
    /// round-off of order 10⁻¹⁶ |u| / (10⁻⁴ v_s), far below what Newton's convergence notices.
    static constexpr double difference_step = 1e-4;

    double coefficient, slip_velocity;

    /// What particle i touches: particle j (its periodic image shifted by shift), or a wall
    /// (j invalid) whose plane is where n·x = plane, moving at wall_velocity.
    struct Partner
    {
      unsigned int   j = numbers::invalid_unsigned_int;
      Tensor<1, dim> shift, normal, wall_velocity;
      double         plane = 0;
    };

    /// Force and torque rows (V then ω, particle i then j; zero for a wall) of the friction
    /// for the unknowns u (the same layout), the histories taken from the particles.
    PairVector rows(const ParticleSet<dim> &particles, const unsigned int i,
                    const Partner &partner, const NormalForce &normal_force,
                    const std::array<double, 3> &c, const PairVector &u) const;

    void add(ParticleSet<dim> &particles, const unsigned int i, const Partner &partner,
             const NormalForce &normal_force, const std::array<double, 3> &c,
             Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const;
  };
} // namespace fdparticle

#endif
