#ifndef fdparticle_fem_cut_cell_quadrature_h
#define fdparticle_fem_cut_cell_quadrature_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/tria.h>
#include <deal.II/hp/q_collection.h>
#include <deal.II/non_matching/quadrature_generator.h>

#include <fdparticle/fem/introspection.h>
#include <fdparticle/particles/particle_set.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /// What the particles do to one cell.
  enum class CellKind
  {
    fluid,  ///< no particle meets the cell
    inside, ///< the cell lies inside one particle
    cut     ///< a particle surface crosses the cell
  };

  /**
   * Where the integrals over the balls P_k are evaluated (doc/method.md §6 "Integration over
   * the particles", §7). A cell away from every particle gets the ordinary 3-point Gauss rule,
   * exact for the Q2 integrands on affine cells. A cut cell gets either the seed's n-point
   * Gauss rule, every point belonging to the particle that contains it or to the fluid
   * (χ_P tested point by point), or level-set rules on its parts in and out of the balls.
   * This is the one place that decides which point lies in which particle.
   */
  template <int dim>
  class CutCellQuadrature
  {
  public:
    /// The rule on one cell and, for each point, the particle owning it (−1: fluid).
    struct CellRule
    {
      CellKind                kind = CellKind::fluid;
      int                     particle = -1; ///< the particle that meets the cell (first one)
      /// All balls that meet the cell (ParticleSet::meeting), sorted; two or more near a contact.
      std::vector<unsigned int> balls;
      const Quadrature<dim> * quadrature = nullptr;
      std::vector<int>        owner;
      /// A rule made for this cell alone (level set); quadrature then points here.
      Quadrature<dim>         cell_specific;
      bool                    owners_known = false;

      /// Whether some point of the rule lies in a particle (after assign_owners).
      bool has_particle_point() const
      {
        return std::any_of(owner.begin(), owner.end(), [](int k) { return k >= 0; });
      }

      /// The particle fraction θ_K of the cell (doc/method.md §4 "Penalty ramp", §7): 0 for
      /// a fluid cell, 1 inside a particle, else the weights (JxW or the rule's own, which
      /// differ by the constant Jacobian of an axis-aligned cell) at the points a particle
      /// owns over all. A cut cell's owners must be known (assign_owners).
      double particle_fraction(const std::vector<double> &weights) const
      {
        if (kind != CellKind::cut)
          return kind == CellKind::inside ? 1.0 : 0.0;
        AssertDimension(weights.size(), owner.size());
        double inside = 0, total = 0;
        for (unsigned int q = 0; q < weights.size(); ++q)
          {
            total += weights[q];
            inside += (owner[q] >= 0 ? weights[q] : 0.0);
          }
        return inside / total;
      }
    };

    /// How cut cells are integrated.
    enum class Method
    {
      gauss,    ///< the seed's n-point Gauss rule, each point tested inside/outside
      level_set ///< Saye's algorithm on the ball's level set |x − X|² − R² (deal.II 9.4)
    };

    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    const Quadrature<dim> &regular_rule() const { return regular; }
    const Quadrature<dim> &cut_rule() const { return cut; }
    unsigned int           cut_points_per_direction() const { return n_cut_points; }

    /// Which particles meet the cell: fluid, inside or cut (by the cell's vertices and box).
    CellKind classify(const typename Triangulation<dim>::cell_iterator &cell,
                      const ParticleSet<dim> &particles, int &particle) const;

    /// The cell's share of the work in the partition between MPI ranks (deal.II's weight
    /// signal; integers): weight_resolution for a cell no surface cuts,
    /// `Cut cell cost` times that for a cut cell. During refinement cell is the parent of
    /// the cells being weighed, and its kind stands for theirs.
    unsigned int partition_weight(const typename Triangulation<dim>::cell_iterator &cell,
                                  const ParticleSet<dim> &particles) const;
    /// Whether the weights differ from cell to cell (else the plain cell count balances).
    bool weighted_partition() const { return cut_cell_cost != 1; }

    /// The ball whose surface is nearest to the point x of the cell of rule: at a fluid
    /// point of a cut cell, the ball whose radius sets the cut-cell penalties, so a cell
    /// that two balls cut penalizes the fluid near each by that ball's own weight.
    unsigned int nearest_surface(const CellRule &rule, const ParticleSet<dim> &particles,
                                 const Point<dim> &x) const;

    /**
     * Fill rule for the cell; quadrature_points_real are the rule's points mapped to the
     * cell, computed by the caller's FEValues (an affine map is not assumed here).
     */
    void reinit(const typename Triangulation<dim>::cell_iterator &cell,
                const ParticleSet<dim> &particles, CellRule &rule) const;

    /// Set the owners once the real-space points of rule are known (Gauss rule only).
    void assign_owners(const std::vector<Point<dim>> &points,
                       const ParticleSet<dim> &particles, CellRule &rule) const;

    /// The particle fraction θ_K of a cell (CellRule::particle_fraction), its rule made here.
    double particle_fraction(const typename Triangulation<dim>::cell_iterator &cell,
                             const ParticleSet<dim> &particles, const Mapping<dim> &mapping) const;

  private:
    /// The level-set rule of a cut cell (rule.balls known), mapped to the unit cell, with
    /// the owner of each point.
    void generate_level_set_rule(const typename Triangulation<dim>::cell_iterator &cell,
                                 const ParticleSet<dim> &particles, CellRule &rule) const;

    /// Append the rule of box (real coordinates) and the owner of each point (a ball of
    /// balls, or −1): a box that two balls (or two images of one) meet is halved until
    /// each piece meets one at most, up to max_separation_depth halvings.
    void append_rules(const BoundingBox<dim> &box, const ParticleSet<dim> &particles,
                      const std::vector<unsigned int> &balls, const unsigned int depth,
                      std::vector<Point<dim>> &points, std::vector<double> &weights,
                      std::vector<int> &owners) const;

    /**
     * Append to inside and outside the rules (real coordinates) of the parts of box in and
     * out of the shape centred at X (the image that meets the box), from its level set
     * (Shape::level_set). A box whose closure holds the centre is split first (at the
     * centre, then in halves): there the level set has no height direction and deal.II's
     * generator falls back to rules that are wrong by up to 14 % for the Q2 integrands
     * and not mirror symmetric. Whether a piece has a height direction is the shape's
     * answer (Shape::has_height_direction); Q turns the shape (body to world).
     */
    void append_shape_rules(const BoundingBox<dim> &box, const Point<dim> &X,
                            const Shape<dim> &shape, const Tensor<2, dim> &Q,
                            std::vector<Point<dim>> &inside_points,
                            std::vector<double> &    inside_weights,
                            std::vector<Point<dim>> &outside_points,
                            std::vector<double> &    outside_weights) const;

    /**
     * The level-set rules of the cut cells met so far, for the particle geometry of
     * stored_revision (ParticleSet::geometry_revision) and the cells of
     * stored_triangulation (a CellId names the same cell of the same coarse mesh through
     * refinement and repartitioning). The geometry is fixed during a time
     * step (ParticleSet::prepare_step) while the step classifies the cells once and
     * assembles several times (Newton), so each rule is generated once per step instead of
     * at every pass; a new geometry empties the store.
     */
    struct StoredRule
    {
      Quadrature<dim>  quadrature;
      std::vector<int> owner;
    };
    mutable std::map<CellId, StoredRule> stored_rules;
    mutable std::uint64_t                stored_revision      = 0;
    mutable const Triangulation<dim> *   stored_triangulation = nullptr;

    /// The weight of a regular cell in partition_weight: cut-cell costs are kept to 1/16.
    static constexpr unsigned int weight_resolution = 16;
    double         cut_cell_cost = 4;
    Method         cut_method = Method::gauss;
    unsigned int   n_cut_points = 7;
    unsigned int   level_set_order = 6;
    QGauss<dim>    regular = Introspection<dim>::cell_quadrature();
    QGauss<dim>    cut{7};
    hp::QCollection<1>                                     level_set_rules_1d;
    std::unique_ptr<NonMatching::QuadratureGenerator<dim>> generator;
  };
} // namespace fdparticle

#endif
