#ifndef fdparticle_particles_repulsion_law_h
#define fdparticle_particles_repulsion_law_h

#include <fdparticle/particles/normal_contact.h>

namespace fdparticle
{
  /**
   * Glowinski et al.'s short-range repulsion (J. Comput. Phys. 169 (2001) 363–426, eqs.
   * (2.6)–(2.7)) as a force magnitude in terms of the gap g between two surfaces:
   *
   *   F(g) = K (1 − g/ρ)²  for g < ρ,   0 otherwise.
   *
   * Glowinski writes (1/ε)(ρ − g)²; K = ρ²/ε is the force at contact, so the parameters
   * read as a length (the range ρ) and a force (the stiffness K). The same law pushes a
   * ball off a wall (WallRepulsion) and two balls apart (Collisions).
   */
  struct RepulsionLaw
  {
    /**
     * The stiffness of 'auto': this many times the apparent weight W of the ball the
     * contact carries. A ball resting on a wall or on another ball sits where F = W, at
     * g = ρ (1 − √(W/K)) = 0.9 ρ: inside the range, but with 90 % of it left before the
     * surfaces touch.
     */
    static constexpr double stiffness_per_weight = 100;

    double range     = 0;
    double stiffness = 0;

    bool acts(const double gap) const { return gap < range; }

    double force(const double gap) const
    {
      const double s = 1 - gap / range;
      return stiffness * s * s;
    }

    /// dF/dg (negative: the force grows as the gap closes).
    double derivative(const double gap) const { return -2 * stiffness * (1 - gap / range) / range; }

    /// The force and its derivatives as a contact law (it does not depend on the velocity).
    NormalLawValue value(const double gap) const
    {
      return NormalLawValue{force(gap), derivative(gap), 0.0};
    }
  };
} // namespace fdparticle

#endif
