#include <fdparticle/core/parameter_tools.h>
#include <fdparticle/particles/wall_repulsion.h>

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
    prm.leave_subsection();
  }

  template <int dim>
  void WallRepulsion<dim>::initialize(const Domain<dim> &domain, const Fluid<dim> &fluid,
                                      const ParticleSet<dim> &particles,
                                      const double finest_cell_size)
  {
    this->domain = domain;
    rho = range_entry.value_or(finest_cell_size);
    stiffness.resize(particles.size());
    for (unsigned int k = 0; k < particles.size(); ++k)
      stiffness[k] = stiffness_entry.value_or(RepulsionLaw::stiffness_per_weight *
                                              std::abs(particles[k].density - fluid.density) *
                                              particles[k].volume() * fluid.gravity.norm());
  }

  template <int dim>
  void WallRepulsion<dim>::add_to_particle_rows(ParticleSet<dim> &particles,
                                                const std::array<double, 3> &c,
                                                Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const
  {
    if (!on)
      return;
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const Particle<dim> &P = particles[k];
        if (P.first_unknown == numbers::invalid_unsigned_int)
          continue;
        const RepulsionLaw law{rho, stiffness[k]};
        for (const auto &wall : domain.walls_near(P.position_after_step(c), P.radius, rho))
          NormalContact<dim>::wall(particles, k, wall.normal, wall.gap)
            .add(particles, NormalLawValue{law.force(wall.gap), law.derivative(wall.gap), 0.0},
                 c, r_p, D);
      }
  }

  template class WallRepulsion<2>;
  template class WallRepulsion<3>;
} // namespace fdparticle
