#ifndef fdparticle_particles_normal_contact_h
#define fdparticle_particles_normal_contact_h

#include <deal.II/base/tensor.h>

#include <fdparticle/particles/contact_geometry.h>
#include <fdparticle/particles/particle_set.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <array>
#include <functional>

namespace fdparticle
{
  using namespace dealii;

  /// A normal contact law evaluated at one gap g and normal relative velocity v_n: the
  /// force magnitude f (positive pushes the surfaces apart) and its partial derivatives.
  struct NormalLawValue
  {
    double force = 0, d_gap = 0, d_velocity = 0;
  };

  /**
   * The kinematics of one contact and the Newton rows of a force along its normal: the
   * piece the contact models (Collisions, Lubrication) share.
   *
   * A contact is a pair of balls i, j, with n = (X_i − X_j)/|X_i − X_j| (nearest periodic
   * image), or a ball i and a wall, with n the wall's inward normal. The force on i is
   * F = f(g, v_n) n, and −F on j, where g is the gap between the surfaces and
   * v_n = (V_i − V_j)·n the normal relative velocity (positive when they separate).
   *
   * Like every contact force here it is implicit (doc/method.md §12): X is the end-of-step
   * position X^{n+1}(V) = (V − c1 X^n − c2 X^{n−1})/c0 and V the Newton iterate, so
   *
   *   dF/dV_rel = (1/c0) [f_g n nᵀ + (f/d)(I − n nᵀ) + f_v n ((I − n nᵀ) V_rel / d)ᵀ]
   *               + f_v n nᵀ,
   *
   * d = |X_i − X_j|; the terms with 1/d, from the turning normal, are absent at a wall.
   */
  template <int dim>
  class NormalContact
  {
  public:
    /// Balls i and j at offset X_i − X_j and gap g.
    static NormalContact pair(const ParticleSet<dim> &particles, const unsigned int i,
                              const unsigned int j, const Tensor<1, dim> &offset,
                              const double gap);
    /// Ball i at gap g from a wall of inward normal n.
    static NormalContact wall(const ParticleSet<dim> &particles, const unsigned int i,
                              const Tensor<1, dim> &normal, const double gap);
    /**
     * A contact of particles i and j (j = numbers::invalid_unsigned_int: a wall) that are
     * not both balls: the force f(g, v_n) n on i at the contact geometry of the end-of-step
     * positions, −F on j, and with the torque balance the torques arm × (±F) about each
     * centre. contact is the geometry at the end-of-step positions (the caller's, which
     * told it the pair is in range), geometry(δX_i, δX_j) gives it for the positions moved
     * by δX; D by central differences in the velocities (X^{n+1} = (V − c1 X^n −
     * c2 X^{n−1})/c0), step 10⁻⁶ c0 range.
     */
    static void add_shaped(
      ParticleSet<dim> &particles, const unsigned int i, const unsigned int j,
      const ContactGeometry<dim> &contact,
      const std::function<ContactGeometry<dim>(const Tensor<1, dim> &, const Tensor<1, dim> &)>
        &                                                           geometry,
      const std::function<NormalLawValue(double gap, double v_n)> &law, const double range,
      const std::array<double, 3> &c, Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D);

    double gap() const { return g; }
    double normal_velocity() const { return v_n; }

    /**
     * Subtract F from the force-balance rows of the free balls of the contact (their
     * residual is mass × acceleration + λ-force − contact force), add −dF/dV to D (if
     * given), and add F to the contact_force of each ball for output.
     */
    void add(ParticleSet<dim> &particles, const NormalLawValue &f,
             const std::array<double, 3> &c, Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const;

  private:
    unsigned int   i = 0, j = numbers::invalid_unsigned_int;
    Tensor<1, dim> n, relative_velocity;
    /// |X_i − X_j| for a pair; 0 for a wall (the normal does not turn).
    double distance = 0;
    double g = 0, v_n = 0;
  };
} // namespace fdparticle

#endif
