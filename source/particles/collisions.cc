#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/collisions.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <optional>

namespace fdparticle
{
  template <int dim>
  void Collisions<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Collisions");
    {
      prm.declare_entry("Model", "none", Patterns::Selection("none|repulsion|spring-dashpot"),
                        "Contact between particles. none: the run stops when two particles "
                        "overlap. repulsion: a short-range force along the line of centres "
                        "(Glowinski et al. 2001), the law of the wall repulsion. spring-dashpot: "
                        "a spring and a dashpot along the line of centres, active below Range, "
                        "give a bounce with the Restitution coefficient.");
      prm.declare_entry("Range", "auto", Patterns::Anything(),
                        "Gap between two particle surfaces below which the force acts (a "
                        "length), or 'auto': the edge of the finest cells, as for the walls. "
                        "Two particles closer than a cell share cells, which the method "
                        "cannot give two rigid motions.");
      prm.declare_entry("Stiffness", "auto", Patterns::Anything(),
                        "Force at contact (gap 0), or 'auto': 100 times the apparent weight "
                        "|rho_P - rho_f| |P| |g| of the heavier particle of the pair, so a "
                        "particle resting on another sits 0.9 Range above it.");
      prm.declare_entry("Spring stiffness", "auto", Patterns::Anything(),
                        "spring-dashpot: normal force per unit compression Range - gap (in 2D "
                        "per unit length too), or 'auto': Stiffness / Range, so a particle "
                        "resting on another compresses the spring by 1 % of Range.");
      prm.declare_entry("Restitution coefficient", "0.9", Patterns::Double(0, 1),
                        "spring-dashpot: ratio of the normal relative velocities after and "
                        "before a collision of two dry particles; the dashpot dissipates the "
                        "rest. The fluid's own damping comes on top. Resolve the contact "
                        "duration printed at the start with about 10 time steps to get it.");
      prm.declare_entry("Friction coefficient", "0", Patterns::Double(0),
                        "spring-dashpot: Coulomb friction coefficient between particle "
                        "surfaces (tangential force at most this times the normal force, "
                        "with a torque). 0: frictionless. Needs Particles/Angular velocity "
                        "closure = torque balance.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void Collisions<dim>::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    prm.enter_subsection("Collisions");
    const std::string model = prm.get("Model");
    contact_model = (model == "repulsion"      ? Model::repulsion :
                     model == "spring-dashpot" ? Model::spring_dashpot :
                                                 Model::none);
    range_entry = get_auto_or_number(prm, "Range", "Collisions/Range", Zero::refused);
    stiffness_entry =
      get_auto_or_number(prm, "Stiffness", "Collisions/Stiffness", Zero::refused);
    spring_entry = get_auto_or_number(prm, "Spring stiffness", "Collisions/Spring stiffness",
                                      Zero::refused);
    restitution = prm.get_double("Restitution coefficient");
    friction    = prm.get_double("Friction coefficient");
    AssertThrow(friction == 0 || contact_model == Model::spring_dashpot,
                ExcMessage("Collisions/Friction coefficient acts in the spring-dashpot model "
                           "only: set Collisions/Model = spring-dashpot, or the coefficient "
                           "to 0."));
    AssertThrow(restitution > 0,
                ExcMessage("Collisions/Restitution coefficient must be above 0: a perfectly "
                           "plastic contact needs infinite damping. Give a small value such "
                           "as 0.01 instead."));
    prm.leave_subsection();
  }

  template <int dim>
  void Collisions<dim>::initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                                   const ParticleSet<dim> &particles,
                                   const double finest_cell_size)
  {
    range = range_entry.value_or(finest_cell_size);
    search = std::make_unique<PairSearch<dim>>(domain);
    weight.resize(particles.size());
    mass.resize(particles.size());
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        weight[k] = std::abs(particles[k].density - fluid.density) * particles[k].volume() *
                    fluid.gravity.norm();
        mass[k] = particles[k].density * particles[k].volume();
      }
    AssertThrow(friction == 0 || particles.closure() == AngularVelocityClosure::torque_balance,
                ExcMessage("Collisions/Friction coefficient exerts a torque, which the "
                           "kinematic angular-velocity closure has no equation for: use the "
                           "torque balance closure, or no friction."));
    const bool needs_weight =
      (contact_model == Model::repulsion && !stiffness_entry) ||
      (contact_model == Model::spring_dashpot && !stiffness_entry && !spring_entry);
    if (needs_weight)
      for (unsigned int i = 0; i < particles.size(); ++i)
        AssertThrow(weight[i] > 0 || particles.size() == 1 ||
                      particles[i].first_unknown == numbers::invalid_unsigned_int,
                    ExcMessage("Collisions/Stiffness = auto scales with the apparent weight of "
                               "the particles, and particle " + std::to_string(i) +
                               " has none (no gravity, or the fluid's density): give the "
                               "force at contact as a number."));
  }

  template <int dim>
  double Collisions<dim>::spring_stiffness(const unsigned int i, const unsigned int j) const
  {
    return spring_entry ? *spring_entry : law(i, j).stiffness / range;
  }

  template <int dim>
  double Collisions<dim>::effective_mass(const unsigned int i, const unsigned int j,
                                         const ParticleSet<dim> &particles) const
  {
    // A ball that does not move by its force balance is an infinite mass to the other.
    const bool free_i = particles[i].motion == ParticleMotion::free;
    const bool free_j = particles[j].motion == ParticleMotion::free;
    if (free_i != free_j)
      return free_i ? mass[i] : mass[j];
    return mass[i] * mass[j] / (mass[i] + mass[j]);
  }

  template <int dim>
  SpringDashpotLaw Collisions<dim>::spring_dashpot(const unsigned int i, const unsigned int j,
                                                   const ParticleSet<dim> &particles) const
  {
    return SpringDashpotLaw(range, spring_stiffness(i, j), restitution,
                            effective_mass(i, j, particles));
  }

  template <int dim>
  std::string Collisions<dim>::describe(const double dt) const
  {
    if (contact_model != Model::spring_dashpot || weight.empty())
      return "";
    // The shortest contact: each ball against a copy of itself.
    double shortest = std::numeric_limits<double>::max();
    for (unsigned int k = 0; k < weight.size(); ++k)
      shortest = std::min(shortest, SpringDashpotLaw::contact_time(
                                      mass[k] / 2, spring_stiffness(k, k), restitution));
    std::ostringstream out;
    out << "Collisions: spring-dashpot contacts last t_c = " << std::setprecision(3) << shortest
        << " (" << shortest / dt << " time steps; the implicit time integration takes "
        << "energy from a bounce resolved by few steps: a dry bounce comes out 2 % below the "
        << "restitution coefficient with 10 steps, 25 % with 3)";
    return out.str();
  }

  template <int dim>
  RepulsionLaw Collisions<dim>::law(const unsigned int i, const unsigned int j) const
  {
    return RepulsionLaw{range, stiffness_entry.value_or(RepulsionLaw::stiffness_per_weight *
                                                        std::max(weight[i], weight[j]))};
  }

  namespace
  {
    template <int dim>
    void centres_and_radii(const ParticleSet<dim> &particles, const std::array<double, 3> *c,
                           std::vector<Point<dim>> &x, std::vector<double> &r)
    {
      x.resize(particles.size());
      r.resize(particles.size());
      for (unsigned int k = 0; k < particles.size(); ++k)
        {
          x[k] = (c != nullptr ? particles[k].position_after_step(*c) : particles[k].position);
          r[k] = particles[k].bounding_radius();
        }
    }
  } // namespace

  template <int dim>
  void Collisions<dim>::add_to_particle_rows(ParticleSet<dim> &particles,
                                             const std::array<double, 3> &c,
                                             Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const
  {
    if (contact_model == Model::none)
      return;
    Assert(search, ExcMessage("Collisions::initialize was not called."));
    std::vector<Point<dim>> x;
    std::vector<double>     r;
    centres_and_radii(particles, &c, x, r);
    // Friction on the spring-dashpot contact of i and j (shift: the periodic image).
    const auto add_friction = [&](const unsigned int i, const unsigned int j,
                                  const Tensor<1, dim> &shift, const SpringDashpotLaw &spring) {
      ContactFriction<dim>(friction, spring)
        .add_pair(particles, i, j, shift,
                  [&](const double gap, const double normal_velocity) {
                    return spring.value(gap, normal_velocity).force;
                  },
                  c, r_p, D);
    };
    for (const auto &pair : search->pairs(x, r, range))
      {
        const Particle<dim> &A = particles[pair.i], &B = particles[pair.j];
        if (!A.shape->is_isotropic() || !B.shape->is_isotropic())
          {
            // Not two balls: the true gap between the shapes (ContactGeometry), solved
            // once here for the range test and the force.
            const ContactGeometry<dim> contact = ContactGeometry<dim>::pair(A, B, pair.offset);
            if (contact.gap >= range)
              continue;
            const auto geometry = [&](const Tensor<1, dim> &dXi, const Tensor<1, dim> &dXj) {
              return ContactGeometry<dim>::pair(A, B, pair.offset + dXi - dXj);
            };
            const std::optional<SpringDashpotLaw> spring =
              contact_model == Model::repulsion ?
                std::nullopt :
                std::optional<SpringDashpotLaw>(spring_dashpot(pair.i, pair.j, particles));
            const RepulsionLaw repulsion = law(pair.i, pair.j);
            NormalContact<dim>::add_shaped(
              particles, pair.i, pair.j, contact, geometry,
              [&](const double gap, const double v_n) {
                return spring ? spring->value(gap, v_n) : repulsion.value(gap);
              },
              range, c, r_p, D);
            if (spring && friction > 0)
              add_friction(pair.i, pair.j, pair.offset - (x[pair.i] - x[pair.j]), *spring);
            continue;
          }
        const auto contact =
          NormalContact<dim>::pair(particles, pair.i, pair.j, pair.offset, pair.gap);
        if (contact_model == Model::repulsion)
          {
            contact.add(particles, law(pair.i, pair.j).value(pair.gap), c, r_p, D);
            continue;
          }
        const SpringDashpotLaw spring = spring_dashpot(pair.i, pair.j, particles);
        contact.add(particles, spring.value(pair.gap, contact.normal_velocity()), c, r_p, D);
        if (friction > 0)
          add_friction(pair.i, pair.j, pair.offset - (x[pair.i] - x[pair.j]), spring);
      }
  }

  template <int dim>
  void Collisions<dim>::declare_columns(StatisticsTable &statistics) const
  {
    statistics.declare("contacts");
    statistics.declare("min_gap");
  }

  template <int dim>
  void Collisions<dim>::statistics(const ParticleSet<dim> &particles,
                                   StatisticsTable &       statistics) const
  {
    Assert(search, ExcMessage("Collisions::initialize was not called."));
    unsigned int n_contacts = 0;
    std::vector<Point<dim>> x;
    std::vector<double>     r;
    centres_and_radii<dim>(particles, nullptr, x, r);
    const double diameter = (r.empty() ? 0.0 : 2 * *std::max_element(r.begin(), r.end()));
    double       min_gap  = diameter;
    for (const auto &pair : search->pairs(x, r, diameter))
      {
        const double gap =
          ContactGeometry<dim>::pair(particles[pair.i], particles[pair.j], pair.offset).gap;
        min_gap = std::min(min_gap, gap);
        if (gap < range)
          ++n_contacts;
      }
    statistics.set("contacts", n_contacts);
    statistics.set("min_gap", min_gap);
  }

  template class Collisions<2>;
  template class Collisions<3>;
} // namespace fdparticle
