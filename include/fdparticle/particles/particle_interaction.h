#ifndef fdparticle_particles_particle_interaction_h
#define fdparticle_particles_particle_interaction_h

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/base/box.h>
#include <fdparticle/base/fluid.h>
#include <fdparticle/base/statistics_table.h>
#include <fdparticle/particles/particle_set.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <array>
#include <string>

namespace fdparticle
{
  using namespace dealii;

  /**
   * A force between particles, or between particles and walls, that the resolved flow
   * does not give: contact models and lubrication corrections (doc/method.md §12). It
   * works on the ParticleSet alone, not on the mesh, and adds to the particle rows of
   * the Newton system after the assembly: its force at the end-of-step positions
   * X^{n+1}(V) to the force-balance residual, its derivative to the particle block D.
   * The implementations are listed in ParticleInteractions.
   */
  template <int dim>
  class ParticleInteraction
  {
  public:
    virtual ~ParticleInteraction() = default;

    virtual void parse_parameters(ParameterHandler &prm) = 0;
    /// Resolve lengths and stiffnesses that depend on the scene ('auto' entries).
    virtual void initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                            const ParticleSet<dim> &particles,
                            const double            finest_cell_size) = 0;
    /// Whether the scene switched it on.
    virtual bool enabled() const = 0;
    /// Throw a one-line error if the interaction, enabled, cannot serve these particles
    /// (before anything is written).
    virtual void check_scene(const ParticleSet<dim> & /*particles*/) const {}
    /// A line for the start of a run (e.g. a contact time against the time step dt), or "".
    virtual std::string describe(const double /*dt*/) const { return ""; }
    /**
     * Subtract the force at X^{n+1}(V), V from the force-balance rows of the free
     * particles in r_p, its derivative −∂F/∂V from D (if given), and add the force to
     * each particle's contact_force (for output).
     */
    virtual void add_to_particle_rows(ParticleSet<dim> &particles, const std::array<double, 3> &c,
                                      Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const = 0;

    /// Its columns of statistics.csv (none by default), declared once and set each step,
    /// whether it is enabled or not.
    virtual void declare_columns(StatisticsTable & /*statistics*/) const {}
    virtual void statistics(const ParticleSet<dim> & /*particles*/,
                            StatisticsTable & /*statistics*/) const
    {}

  protected:
    /// Throw "ENTRY: WHAT is modelled between spheres and disks, and particle k is an
    /// ellipse; FIX." if a particle is not a ball.
    static void require_balls(const ParticleSet<dim> &particles, const std::string &entry,
                              const std::string &what, const std::string &fix)
    {
      for (unsigned int k = 0; k < particles.size(); ++k)
        AssertThrow(particles[k].shape->is_isotropic(),
                    ExcMessage(entry + ": " + what + " is modelled between spheres and disks, "
                               "and particle " + std::to_string(k) + " is an " +
                               particles[k].shape->name() + "; " + fix + "."));
    }
  };
} // namespace fdparticle

#endif
