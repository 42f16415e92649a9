#ifndef fdparticle_particles_particle_interactions_h
#define fdparticle_particles_particle_interactions_h

#include <fdparticle/particles/particle_interaction.h>

#include <memory>
#include <string>
#include <vector>

namespace fdparticle
{
  /**
   * Every ParticleInteraction of a scene, in a fixed order: the wall repulsion or contact
   * (WallRepulsion), the pair contacts (Collisions) and the lubrication correction
   * (Lubrication). A new interaction is a class derived from ParticleInteraction, added
   * to declare_parameters() and parse_parameters() here.
   */
  template <int dim>
  class ParticleInteractions
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);
    /// ParticleInteraction::check_scene of each.
    void        check_scene(const ParticleSet<dim> &particles) const;

    void initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                    const ParticleSet<dim> &particles, const double finest_cell_size);

    /// The interactions' lines for the start of a run (none for those with nothing to say).
    std::vector<std::string> describe(const double dt) const;

    /// Reset every particle's contact_force, then let each enabled interaction add its
    /// force to the particle rows and to contact_force (ParticleInteraction).
    void add_to_particle_rows(ParticleSet<dim> &particles, const std::array<double, 3> &c,
                              Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const;

    /// The interactions' columns of statistics.csv, and their values for a step.
    void declare_columns(StatisticsTable &statistics) const;
    void statistics(const ParticleSet<dim> &particles, StatisticsTable &statistics) const;

  private:
    std::vector<std::unique_ptr<ParticleInteraction<dim>>> list;
  };
} // namespace fdparticle

#endif
