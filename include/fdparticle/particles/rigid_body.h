#ifndef fdparticle_particles_rigid_body_h
#define fdparticle_particles_rigid_body_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <Eigen/Geometry>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Rigid-body algebra in 2D and 3D with one vocabulary: an angular velocity always has
   * three components (2D uses only the z one), so the same code writes ω × r, the
   * velocity gradient of a rotation and the torque of a force in both dimensions.
   */
  template <int dim>
  struct RigidBody
  {
    /// Number of rotational degrees of freedom: 1 in 2D (ω_z), 3 in 3D.
    static constexpr unsigned int n_rotations = (dim == 2 ? 1 : 3);
    /// Translational plus rotational unknowns of one free particle.
    static constexpr unsigned int n_unknowns = dim + n_rotations;

    /// Which of ω's three components the rotational unknown j (0..n_rotations-1) is: z in 2D.
    static unsigned int rotation_component(const unsigned int j) { return dim == 2 ? 2 : j; }

    /// The 3-vector of a rotational component j (0..n_rotations-1): e_z in 2D.
    static Tensor<1, 3> rotation_axis(const unsigned int j);

    /// ω × r, restricted to the dim velocity components.
    static Tensor<1, dim> cross(const Tensor<1, 3> &omega, const Tensor<1, dim> &r);

    /// Gradient of the rigid rotation field x ↦ ω × (x − X): W_il = ∂_l (ω × r)_i.
    static Tensor<2, dim> rotation_gradient(const Tensor<1, 3> &omega);

    /// r × f as a 3-vector (2D: only z is non-zero).
    static Tensor<1, 3> moment(const Tensor<1, dim> &r, const Tensor<1, dim> &f);

    /// Curl of a velocity gradient G_il = ∂_l u_i as a 3-vector (2D: z component only).
    static Tensor<1, 3> curl(const Tensor<2, dim> &grad_u);

    /// The rotation vector of a unit quaternion: angle (in [0, π]) times axis.
    static Tensor<1, 3> rotation_vector(const Eigen::Quaterniond &q);

    /// The rotation matrix (body to world) of a unit quaternion q, R v = q v q*: its
    /// leading n × n block, n = dim for positions and shapes (in 2D q turns about z and the
    /// block is the turn in the plane), n = 3 for the inertia tensor.
    template <int n = dim>
    static Tensor<2, n> rotation_matrix(const Eigen::Quaterniond &q);

    /// Advance a unit quaternion by the rotation ω Δt (exact for constant ω in the step).
    static Eigen::Quaterniond rotate(const Eigen::Quaterniond &q,
                                     const Tensor<1, 3> &      omega,
                                     const double              dt);
  };
} // namespace fdparticle

#endif
