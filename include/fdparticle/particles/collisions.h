#ifndef fdparticle_particles_collisions_h
#define fdparticle_particles_collisions_h

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/core/fluid.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/particles/pair_search.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/particles/repulsion_law.h>

#include <Eigen/Dense>

#include <array>
#include <memory>
#include <optional>
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
   *
   * Like the wall repulsion the force is evaluated at the end-of-step positions X^{n+1}(V)
   * and is implicit: its derivative couples the two particles' rows of the Newton matrix's
   * particle block. Pairs out of range are found by a cell list (PairSearch) and cost
   * nothing further.
   */
  template <int dim>
  class Collisions
  {
  public:
    enum class Model
    {
      none,
      repulsion
    };

    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    /// Resolve the 'auto' defaults: ρ = h_finest; K = 100 × apparent weight of the
    /// heavier ball of each pair.
    void initialize(const Domain<dim> &domain, const Fluid<dim> &fluid,
                    const ParticleSet<dim> &particles, const double finest_cell_size);

    Model model() const { return contact_model; }

    /**
     * Subtract the contact force at X^{n+1}(V) from the force-balance rows of the free
     * particles, and its derivative −∂F/∂V from the particle block D (a pair of free
     * particles couples their rows). Adds F to each particle's contact_force for output.
     */
    void add_to_particle_rows(ParticleSet<dim> &particles, const std::array<double, 3> &c,
                              Eigen::VectorXd &r_p, Eigen::MatrixXd *D) const;

    /// Pairs of balls closer than the contact range at their current positions, and the
    /// smallest gap between two balls, capped at the diameter of the largest ball (the
    /// reach of the search: a larger gap means no ball is near another), for
    /// statistics.csv.
    void statistics(const ParticleSet<dim> &particles, unsigned int &n_contacts,
                    double &min_gap) const;

  private:
    Model  contact_model = Model::none;
    /// The entries as read; empty for 'auto'.
    std::optional<double> range_entry, stiffness_entry;
    double range = 0;
    /// Apparent weight of each ball, |ρ_k − ρ_f| |P_k| |g|.
    std::vector<double>              weight;
    std::unique_ptr<PairSearch<dim>> search;

    RepulsionLaw law(const unsigned int i, const unsigned int j) const;
  };
} // namespace fdparticle

#endif
