#ifndef fdparticle_particles_spring_dashpot_law_h
#define fdparticle_particles_spring_dashpot_law_h

#include <fdparticle/particles/normal_contact.h>

#include <cmath>

namespace fdparticle
{
  /**
   * The linear soft-sphere contact of doc/method.md §12 as a force magnitude in terms of
   * the gap g between two surfaces and their normal relative velocity v_n (positive as
   * they separate): a spring compressed by δ = ρ − g and a dashpot,
   *
   *   f(g, v_n) = k (ρ − g) − γ v_n   for g < ρ,   0 otherwise.
   *
   * The damping γ = 2 ζ √(m_eff k), ζ = −ln e / √(π² + ln² e), gives a dry contact of
   * effective mass m_eff the restitution coefficient e; it lasts
   * t_c = √(m_eff/k) √(π² + ln² e). Two balls (Collisions) have m_eff = m_i m_j/(m_i + m_j);
   * a ball against a wall or a ball that does not move (WallRepulsion) m_eff = m_i.
   */
  struct SpringDashpotLaw
  {
    double range = 0, stiffness = 0, damping = 0;
    /// t_c of the dry contact.
    double duration = 0;

    SpringDashpotLaw(const double range, const double stiffness, const double restitution,
                     const double effective_mass)
      : range(range)
      , stiffness(stiffness)
      , damping(2 * damping_ratio(restitution) * std::sqrt(effective_mass * stiffness))
      , duration(contact_time(effective_mass, stiffness, restitution))
    {}

    static double damping_ratio(const double restitution)
    {
      const double log_e = std::log(restitution);
      return -log_e / std::sqrt(M_PI * M_PI + log_e * log_e);
    }

    static double contact_time(const double effective_mass, const double stiffness,
                               const double restitution)
    {
      const double log_e = std::log(restitution);
      return std::sqrt(effective_mass / stiffness) * std::sqrt(M_PI * M_PI + log_e * log_e);
    }

    /// The force and its derivatives. The linear model acts for the whole compression,
    /// including the short pull of the dashpot as the surfaces part: the restitution
    /// formula assumes it (cutting the force at 0 instead returns more energy: 0.40 for
    /// e = 0.3).
    NormalLawValue value(const double gap, const double normal_velocity) const
    {
      if (gap >= range)
        return NormalLawValue{};
      return NormalLawValue{stiffness * (range - gap) - damping * normal_velocity, -stiffness,
                            -damping};
    }
  };
} // namespace fdparticle

#endif
