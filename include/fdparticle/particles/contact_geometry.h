#ifndef fdparticle_particles_contact_geometry_h
#define fdparticle_particles_contact_geometry_h

#include <deal.II/base/tensor.h>

#include <fdparticle/particles/particle_set.h>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Where two particles, or a particle and a wall, are closest: the gap between the
   * surfaces, the contact normal n (from particle j to particle i; a wall's inward normal)
   * and the arms from each centre to its contact point (doc/method.md §12, §13). Between
   * balls n lies along the line of centres and the arms along n; otherwise n maximises
   * the gap along it, n·d − h_i(−n) − h_j(n) (d = X_i − X_j, h the support function), which
   * for convex shapes is their distance, negative when they overlap.
   */
  template <int dim>
  struct ContactGeometry
  {
    double         gap = 0;
    Tensor<1, dim> normal, arm_i, arm_j;
    /// Whether n is the direction of the line of centres (two balls), so that it turns
    /// as the centres move.
    bool along_centres = true;

    /// Particles i and j at offset X_i − X_j (nearest image). Two balls: the gap
    /// |X_i − X_j| − R_i − R_j, as PairSearch computes it.
    static ContactGeometry pair(const Particle<dim> &i, const Particle<dim> &j,
                                const Tensor<1, dim> &offset);
    /// Particle i and a wall of inward normal n at ball_gap from its bounding ball.
    static ContactGeometry wall(const Particle<dim> &i, const Tensor<1, dim> &normal,
                                const double ball_gap);
  };
} // namespace fdparticle

#endif
