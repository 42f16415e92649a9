#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/contact_friction.h>
#include <fdparticle/particles/wall_repulsion.h>

#include <iomanip>
#include <limits>
#include <sstream>
#include <optional>

namespace fdparticle
{
  template <int dim>
  void WallRepulsion<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Wall repulsion");
    {
      prm.declare_entry("Enabled", "true", Patterns::Bool(),
                        "Push particles off the walls with a short-range force (Glowinski et "
                        "al. 2001) instead of stopping the run when a ball touches a wall.");
      prm.declare_entry("Range", "auto", Patterns::Anything(),
                        "Gap below which the force acts (a length), or 'auto': the edge of the "
                        "finest cells (base mesh refined by the global and particle refinement "
                        "levels), Glowinski's choice.");
      prm.declare_entry("Stiffness", "auto", Patterns::Anything(),
                        "Force at contact (gap 0), or 'auto': 100 times each ball's apparent "
                        "weight |rho_P - rho_f| |P| |g|, so a ball rests at 0.9 Range off the "
                        "floor. With no gravity 'auto' gives no force: give a number.");
      prm.declare_entry("Model", "repulsion", Patterns::Selection("repulsion|spring-dashpot"),
                        "The law of the force. repulsion: Glowinski et al.'s force, growing "
                        "quadratically as the gap closes below Range; a ball comes to rest above "
                        "the wall. spring-dashpot: a spring and a dashpot active below Range "
                        "bounce a ball off the wall with the Restitution coefficient, with "
                        "optional friction.");
      prm.declare_entry("Spring stiffness", "auto", Patterns::Anything(),
                        "spring-dashpot: normal force per unit compression Range - gap (in 2D "
                        "per unit length too), or 'auto': Stiffness / Range, so a ball resting "
                        "on a wall compresses the spring by 1 % of Range.");
      prm.declare_entry("Restitution coefficient", "0.9", Patterns::Double(0, 1),
                        "spring-dashpot: ratio of a dry ball's normal velocity after and "
                        "before it hits a wall; the dashpot dissipates the rest. The fluid's "
                        "own damping comes on top. Resolve the contact duration printed at the "
                        "start with about 10 time steps to get it.");
      prm.declare_entry("Friction coefficient", "0", Patterns::Double(0),
                        "spring-dashpot: Coulomb friction coefficient between a particle and a wall "
                        "(tangential force at most this times the normal force, against sliding, "
                        "with a torque): a ball thrown along a wall starts rolling. 0: "
                        "frictionless. Needs Particles/Angular velocity closure = torque balance.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void WallRepulsion<dim>::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    prm.enter_subsection("Wall repulsion");
    on = prm.get_bool("Enabled");
    range_entry = get_auto_or_number(prm, "Range", "Wall repulsion/Range", Zero::refused);
    stiffness_entry =
      get_auto_or_number(prm, "Stiffness", "Wall repulsion/Stiffness", Zero::allowed);
    spring_dashpot = (prm.get("Model") == "spring-dashpot");
    spring_entry   = get_auto_or_number(prm, "Spring stiffness", "Wall repulsion/Spring stiffness",
                                      Zero::refused);
    restitution = prm.get_double("Restitution coefficient");
    friction    = prm.get_double("Friction coefficient");
    AssertThrow(friction == 0 || spring_dashpot,
                ExcMessage("Wall repulsion/Friction coefficient acts in the spring-dashpot "
                           "model only: set Wall repulsion/Model = spring-dashpot, or the "
                           "coefficient to 0."));
    AssertThrow(restitution > 0 || !spring_dashpot,
                ExcMessage("Wall repulsion/Restitution coefficient must be above 0: a "
                           "perfectly plastic contact needs infinite damping. Give a small "
                           "value such as 0.01 instead."));
    prm.leave_subsection();
  }

  template <int dim>
  void WallRepulsion<dim>::initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                                      const ParticleSet<dim> &particles,
                                      const double finest_cell_size)
  {
    this->domain = domain;
    rho = range_entry.value_or(finest_cell_size);
    stiffness.resize(particles.size());
    mass.resize(particles.size());
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        stiffness[k] = stiffness_entry.value_or(RepulsionLaw::stiffness_per_weight *
                                                std::abs(particles[k].density - fluid.density) *
                                                particles[k].volume() * fluid.gravity.norm());
        mass[k] = particles[k].density * particles[k].volume();
      }
    AssertThrow(!on || friction == 0 ||
                  particles.closure() == AngularVelocityClosure::torque_balance,
                ExcMessage("Wall repulsion/Friction coefficient exerts a torque, which the "
                           "kinematic angular-velocity closure has no equation for: use the "
                           "torque balance closure, or no friction."));
    if (on && spring_dashpot && !spring_entry)
      for (unsigned int k = 0; k < particles.size(); ++k)
        AssertThrow(stiffness[k] > 0 || particles[k].first_unknown == numbers::invalid_unsigned_int,
                    ExcMessage("Wall repulsion/Model = spring-dashpot needs a spring, and "
                               "particle " + std::to_string(k) + " has none: its Stiffness "
                               "is 0, or 'auto' with no apparent weight (no gravity, or the "
                               "fluid's density). Give the force at contact or the Spring "
                               "stiffness as a number."));
  }

  template <int dim>
  SpringDashpotLaw WallRepulsion<dim>::spring(const unsigned int k) const
  {
    // The wall does not move by any force: the ball's own mass is the effective mass.
    return SpringDashpotLaw(rho, spring_entry.value_or(stiffness[k] / rho), restitution, mass[k]);
  }

  template <int dim>
  std::string WallRepulsion<dim>::describe(const double dt) const
  {
    if (!on || !spring_dashpot || mass.empty())
      return "";
    double shortest = std::numeric_limits<double>::max();
    for (unsigned int k = 0; k < mass.size(); ++k)
      if (const SpringDashpotLaw law = spring(k); law.stiffness > 0)
        shortest = std::min(shortest, law.duration);
    if (shortest == std::numeric_limits<double>::max())
      return "";
    std::ostringstream out;
    out << "Wall repulsion: spring-dashpot contacts last t_c = " << std::setprecision(3)
        << shortest << " (" << shortest / dt << " time steps)";
    return out.str();
  }

  template <int dim>
  void WallRepulsion<dim>::add_to_particle_rows(ParticleSet<dim> &particles,
                                                const std::array<double, 3> &c,
                                                Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const
  {
    if (!on)
      return;
    // Friction on the spring-dashpot contact of particle k with a wall.
    const auto add_friction = [&](const unsigned int k, const typename Box<dim>::WallGap &wall,
                                  const SpringDashpotLaw &spring_k) {
      ContactFriction<dim>(friction, spring_k)
        .add_wall(particles, k, wall,
                  [&](const double gap, const double normal_velocity) {
                    return spring_k.value(gap, normal_velocity).force;
                  },
                  c, r_p, D);
    };
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const Particle<dim> &P = particles[k];
        if (P.first_unknown == numbers::invalid_unsigned_int)
          continue;
        const RepulsionLaw law{rho, stiffness[k]};
        for (const auto &wall : domain.walls_near(P.position_after_step(c), P.bounding_radius(), rho))
          {
            if (!P.shape->is_isotropic())
              {
                // Not a ball: the gap from its point nearest the wall (ContactGeometry).
                const ContactGeometry<dim> contact =
                  ContactGeometry<dim>::wall(P, wall.normal, wall.gap);
                if (contact.gap >= rho)
                  continue;
                const std::optional<SpringDashpotLaw> spring_k =
                  spring_dashpot ? std::optional<SpringDashpotLaw>(spring(k)) : std::nullopt;
                NormalContact<dim>::add_shaped(
                  particles, k, numbers::invalid_unsigned_int, contact,
                  [&](const Tensor<1, dim> &dX, const Tensor<1, dim> &) {
                    return ContactGeometry<dim>::wall(P, wall.normal, wall.gap + wall.normal * dX);
                  },
                  [&](const double gap, const double v_n) {
                    return spring_k ? spring_k->value(gap, v_n) : law.value(gap);
                  },
                  rho, c, r_p, D);
                if (spring_k && friction > 0)
                  add_friction(k, wall, *spring_k);
                continue;
              }
            const auto contact = NormalContact<dim>::wall(particles, k, wall.normal, wall.gap);
            if (!spring_dashpot)
              {
                contact.add(particles, law.value(wall.gap), c, r_p, D);
                continue;
              }
            const SpringDashpotLaw spring_k = spring(k);
            contact.add(particles, spring_k.value(wall.gap, contact.normal_velocity()), c, r_p, D);
            if (friction > 0)
              add_friction(k, wall, spring_k);
          }
      }
  }

  template class WallRepulsion<2>;
  template class WallRepulsion<3>;
} // namespace fdparticle
