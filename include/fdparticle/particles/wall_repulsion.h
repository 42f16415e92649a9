#ifndef fdparticle_particles_wall_repulsion_h
#define fdparticle_particles_wall_repulsion_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <fdparticle/base/box.h>
#include <fdparticle/base/fluid.h>
#include <fdparticle/particles/normal_contact.h>
#include <fdparticle/particles/particle_interaction.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/particles/repulsion_law.h>
#include <fdparticle/particles/spring_dashpot_law.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Short-range particle–wall contact (subsection Wall repulsion), a force F n normal to
   * each wall of inward normal n, F a law of the gap g between the ball and the wall:
   *
   * - repulsion: Glowinski et al.'s RepulsionLaw (J. Comput. Phys. 169 (2001) 363–426,
   *   eq. (2.7)). A settling ball rests where F equals its apparent weight W: at
   *   g = ρ (1 − √(W/K)).
   * - spring-dashpot: the SpringDashpotLaw of the ball against an immovable wall
   *   (m_eff = the ball's mass), which bounces a dry ball with the restitution
   *   coefficient, and optional Coulomb friction (ContactFriction) against the wall's
   *   motion, which makes a ball sliding on a wall roll.
   *
   * The force is evaluated at the end-of-step position X^{n+1}(V) of the BDF formula
   * ((F6) as implemented, doc/method.md §2), so it is implicit: its derivative enters the
   * particle block of the Newton matrix, ∂F/∂V = (∂F/∂X) / c0. An explicit force this stiff
   * would need Glowinski's sub-cycling. Particles farther than ρ from every wall cost
   * nothing.
   */
  template <int dim>
  class WallRepulsion : public ParticleInteraction<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm) override;

    /// Resolve the 'auto' defaults: ρ = h_finest, K = 100 × apparent weight of each ball,
    /// and the spring's k = K/ρ.
    void initialize(const Box<dim> &domain, const Fluid<dim> &fluid,
                    const ParticleSet<dim> &particles, const double finest_cell_size) override;

    bool enabled() const override { return on; }

    /// For the log: the spring-dashpot contact duration of the shortest wall contact
    /// against the time step dt; empty for the repulsion.
    std::string describe(const double dt) const override;

    /**
     * Subtract F(X^{n+1}(V)) from the force-balance rows of the free particles (their
     * residual is ρ-weighted acceleration + λ-force − F), and −∂F/∂V from the diagonal
     * block. Also adds F to each particle's contact_force for output.
     */
    void add_to_particle_rows(ParticleSet<dim> &particles, const std::array<double, 3> &c,
                              Eigen::VectorXd &r_p, Eigen::SparseMatrix<double> *D) const override;

  private:
    bool                  on = true, spring_dashpot = false;
    /// The entries as read; empty for 'auto'.
    std::optional<double> range_entry, stiffness_entry, spring_entry;
    double                rho = 0, restitution = 1, friction = 0;
    std::vector<double>   stiffness; // K per particle
    std::vector<double>   mass;      // dry mass ρ_k |P_k| per particle
    Box<dim>           domain;

    SpringDashpotLaw spring(const unsigned int k) const;
  };
} // namespace fdparticle

#endif
