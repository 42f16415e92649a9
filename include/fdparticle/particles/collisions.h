#ifndef fdparticle_particles_collisions_h
#define fdparticle_particles_collisions_h

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/base/fluid.h>
#include <fdparticle/base/box.h>
#include <fdparticle/particles/contact_friction.h>
#include <fdparticle/particles/normal_contact.h>
#include <fdparticle/particles/pair_search.h>
#include <fdparticle/particles/particle_interaction.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/particles/repulsion_law.h>
#include <fdparticle/particles/spring_dashpot_law.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Contact between particles (subsection Collisions), chosen per scene:
   *
   * - none: no force; the run stops with a message when two balls overlap
   *   (ParticleSet::check_positions), as a scene without contacts should.
   * - repulsion: Glowinski et al.'s short-range force (J. Comput. Phys. 169 (2001)
   *   363–426, eq. (2.6)), the RepulsionLaw of the gap g = |X_i − X_j| − R_i − R_j along
   *   the line of centres, F_i = F(g) n = −F_j with n = (X_i − X_j)/|X_i − X_j|, with the
   *   range and the stiffness that the wall repulsion uses.
   * - spring-dashpot: a linear soft-sphere contact (SpringDashpotLaw) acting from the same
   *   range: F_i = (k δ − γ v_n) n with the compression δ = ρ − g > 0 and v_n = (V_i − V_j)·n,
   *   damped so that a dry pair bounces with the restitution coefficient e. The contact
   *   starts a cell before the surfaces touch, as Kempe & Fröhlich (J. Fluid Mech. 709
   *   (2012) 445–489) lengthen theirs: balls closer than a cell share cells, whose one
   *   velocity field cannot follow two rigid motions, and there the discrete flow stops an
   *   approaching ball with a force that depends on the mesh rather than on μ
   *   (doc/particles.md). With a friction coefficient μ_c > 0 the contact also has Coulomb
   *   friction (ContactFriction).
   *
   * The forces are evaluated at the end-of-step positions X^{n+1}(V) and velocities V and
   * are implicit (NormalContact): their derivatives couple the two particles' rows of the
   * Newton matrix's particle block, so a stiff spring neither explodes nor needs sub-steps;
   * only the bounce's restitution needs t_c resolved by the time step. Pairs out of reach
   * are found by a cell list (PairSearch) and cost nothing further.
   */
  template <int dim>
  class Collisions : public ParticleInteraction<dim>
  {
  public:
    enum class Model
    {
      none,
      repulsion,
      spring_dashpot
    };

    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm) override;

    /// Resolve the 'auto' defaults: ρ = h_finest; K = 100 × the apparent weight of the
    /// heavier ball of each pair, and the spring's k = K/ρ.
    void initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                    const ParticleSet<dim> &particles, const double finest_cell_size) override;

    Model model() const { return contact_model; }
    bool  enabled() const override { return contact_model != Model::none; }

    /// For the log: the spring-dashpot contact duration of the stiffest pair against the
    /// time step dt; empty for the other models.
    std::string describe(const double dt) const override;

    /**
     * Subtract the contact force at X^{n+1}(V) from the force-balance rows of the free
     * particles, and its derivative −∂F/∂V from the particle block D (a pair of free
     * particles couples their rows). Adds F to each particle's contact_force for output.
     */
    void add_to_particle_rows(ParticleSet<dim> &particles, const std::array<double, 3> &c,
                              Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const override;

    /// statistics.csv's contacts, the pairs of balls closer than the contact range at
    /// their current positions, and min_gap, the smallest gap between two balls, capped
    /// at the diameter of the largest ball (the reach of the search: a larger gap means
    /// no ball is near another).
    void declare_columns(StatisticsTable &statistics) const override;
    void statistics(const ParticleSet<dim> &particles,
                    StatisticsTable &       statistics) const override;

  private:
    Model  contact_model = Model::none;
    /// The entries as read; empty for 'auto'.
    std::optional<double> range_entry, stiffness_entry, spring_entry;
    double range = 0, restitution = 1, friction = 0;
    /// Apparent weight |ρ_k − ρ_f| |P_k| |g| and dry mass ρ_k |P_k| of each ball.
    std::vector<double>              weight, mass;
    std::unique_ptr<PairSearch<dim>> search;

    RepulsionLaw     law(const unsigned int i, const unsigned int j) const;
    SpringDashpotLaw spring_dashpot(const unsigned int i, const unsigned int j,
                                    const ParticleSet<dim> &particles) const;
    double           spring_stiffness(const unsigned int i, const unsigned int j) const;
    double effective_mass(const unsigned int i, const unsigned int j,
                          const ParticleSet<dim> &particles) const;
  };
} // namespace fdparticle

#endif
