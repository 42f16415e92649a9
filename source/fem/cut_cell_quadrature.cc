#include <deal.II/base/function.h>
#include <deal.II/hp/q_collection.h>

#include <fdparticle/fem/cut_cell_quadrature.h>

#include <algorithm>

#include <cmath>
#include <limits>

namespace fdparticle
{
  namespace
  {
    /**
     * A box goes to deal.II's generator only if, in some direction d, the gap between the
     * ball's centre X and the box is at least this fraction of the distance from X to the
     * box's farthest corner: then |∂ψ/∂x_d| is bounded away from zero relative to |∇ψ| and
     * d is a height direction with a bounded slope. Closer boxes are split. On balls with
     * R/h = 1.2 and 2.4 (tests/unit/level_set_quadrature.cc) the errors are the same for
     * 0.15 to 0.3; 0 (no splitting) leaves cells 44 % wrong, 0.35 splits into boxes the
     * generator handles worse. 0.2 sits inside that plateau.
     */
    constexpr double min_height_slope = 0.2;

    /// Halvings of a cell that two balls meet, until each piece meets one ball at most.
    /// A piece meets two balls only if their gap is below its diagonal: 6 halvings
    /// separate balls 0.03 h apart in 3D (0.02 h in 2D), closer than the collision models
    /// let them come at the default ranges. A piece still meeting two balls takes Gauss
    /// points, each owned by the ball that contains it.
    constexpr unsigned int max_separation_depth = 6;

    /**
     * Halvings deal.II's generator may make of a box before it gives up and puts one
     * midpoint there, owned by the side of the level set at that point. It gives up where
     * a face of the box is tangent to the sphere at a point of that face (the face's
     * restriction of ψ has a double root, definite nowhere around it): R a whole number of
     * cells from a vertex-aligned centre, as scenes are often set up. For a ball of R = 2h
     * tangent to such faces (tests/unit/level_set_quadrature.cc) the generator's default
     * of 4 leaves the cell's particle fraction 1.6e-4 wrong, 12 leaves 3e-9. Whether the
     * tangent point lies just inside or outside a face (round-off) decides between that
     * error and none, so a large error makes mirror-image cells differ and a sphere on a
     * symmetry plane drift off it. 12 adds about 430 points a split, to those cells only.
     */
    constexpr unsigned int max_generator_splits = 12;
  } // namespace

  template <int dim>
  void CutCellQuadrature<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quadrature");
    {
      prm.declare_entry("Cut cells", "gauss", Patterns::Selection("gauss|level set"),
                        "gauss: the seed's rule, 'Gauss points in cut cells' per direction, each "
                        "point counted for the particle that contains it (integrals jump as "
                        "points cross the surface). level set: rules on the parts of the cell "
                        "inside and outside the ball (Saye 2015), smooth in the particle "
                        "position.");
      prm.declare_entry("Gauss points in cut cells", "7", Patterns::Integer(1, 30),
                        "Gauss points per direction in cells cut by a particle surface (gauss "
                        "rule); each point counts for the particle that contains it. 7: the "
                        "seed's choice.");
      prm.declare_entry("Level set order", "6", Patterns::Integer(1, 12),
                        "Points of the 1D Gauss rule the level-set rules are built from (1 to 12; "
                        "error ~ h^(2n) for smooth surfaces). In 3D they set the assembly's cost: "
                        "lower it (e.g. 4) for speed at a small loss of accuracy (doc/method.md "
                        "§7).");
      prm.declare_entry("Cut cell cost", "4", Patterns::Double(1, 1000),
                        "Work of a cut cell relative to a regular one, for the partition of the "
                        "mesh between MPI ranks, rebalanced at every refinement and when the most "
                        "loaded rank exceeds 1.1 times the mean load. 1: equal cell counts, never "
                        "rebalanced. The default balances level-set assembly (doc/particles.md).");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void CutCellQuadrature<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quadrature");
    {
      n_cut_points = prm.get_integer("Gauss points in cut cells");
      cut = QGauss<dim>(n_cut_points);
      cut_method = (prm.get("Cut cells") == "level set" ? Method::level_set : Method::gauss);
      level_set_order = prm.get_integer("Level set order");
      cut_cell_cost   = prm.get_double("Cut cell cost");
      stored_rules.clear(); // made with the former settings
      stored_revision = 0;
      // The generator keeps a reference to its 1D rules: they must outlive it.
      generator.reset();
      level_set_rules_1d = hp::QCollection<1>(QGauss<1>(level_set_order));
      NonMatching::AdditionalQGeneratorData data;
      data.max_box_splits = max_generator_splits;
      generator = std::make_unique<NonMatching::QuadratureGenerator<dim>>(level_set_rules_1d, data);
    }
    prm.leave_subsection();
  }

  namespace
  {
    /// Fluid, inside or cut, given the balls that meet the cell (sorted): the first one
    /// decides, as balls do not overlap.
    template <int dim>
    CellKind kind_of(const typename Triangulation<dim>::cell_iterator &cell,
                     const ParticleSet<dim> &particles, const std::vector<unsigned int> &balls)
    {
      if (balls.empty())
        return CellKind::fluid;
      const Particle<dim> &p = particles[balls.front()];
      bool all_inside = true;
      for (const unsigned int v : cell->vertex_indices())
        all_inside = all_inside && p.contains(cell->vertex(v));
      return all_inside ? CellKind::inside : CellKind::cut;
    }
  } // namespace

  template <int dim>
  CellKind CutCellQuadrature<dim>::classify(const typename Triangulation<dim>::cell_iterator &cell,
                                            const ParticleSet<dim> &particles,
                                            int &                   particle) const
  {
    const std::vector<unsigned int> balls = particles.meeting(cell->bounding_box());
    particle = balls.empty() ? -1 : int(balls.front());
    return kind_of<dim>(cell, particles, balls);
  }

  template <int dim>
  unsigned int
  CutCellQuadrature<dim>::partition_weight(const typename Triangulation<dim>::cell_iterator &cell,
                                           const ParticleSet<dim> &particles) const
  {
    int k;
    return classify(cell, particles, k) == CellKind::cut ?
             static_cast<unsigned int>(std::lround(cut_cell_cost * weight_resolution)) :
             weight_resolution;
  }

  template <int dim>
  unsigned int CutCellQuadrature<dim>::nearest_surface(const CellRule &         rule,
                                                       const ParticleSet<dim> &particles,
                                                       const Point<dim> &      x) const
  {
    Assert(!rule.balls.empty(), ExcMessage("No ball meets this cell."));
    unsigned int nearest = rule.balls.front();
    double       gap = std::numeric_limits<double>::max();
    for (const unsigned int k : rule.balls)
      {
        const double g = particles[k].shape->surface_distance(particles[k].body_offset(x));
        if (g < gap)
          {
            gap = g;
            nearest = k;
          }
      }
    return nearest;
  }

  template <int dim>
  void CutCellQuadrature<dim>::reinit(const typename Triangulation<dim>::cell_iterator &cell,
                                      const ParticleSet<dim> &particles,
                                      CellRule &              rule) const
  {
    rule.balls = particles.meeting(cell->bounding_box());
    rule.kind = kind_of<dim>(cell, particles, rule.balls);
    rule.particle = rule.balls.empty() ? -1 : int(rule.balls.front());
    rule.quadrature = (rule.kind == CellKind::cut ? &cut : &regular);
    rule.owner.assign(rule.quadrature->size(), rule.kind == CellKind::fluid ? -1 : rule.particle);
    rule.owners_known = (rule.kind != CellKind::cut);
    if (rule.kind != CellKind::cut || cut_method != Method::level_set)
      return;
    if (stored_revision != particles.geometry_revision() ||
        stored_triangulation != &cell->get_triangulation())
      {
        stored_rules.clear();
        stored_revision      = particles.geometry_revision();
        stored_triangulation = &cell->get_triangulation();
      }
    const CellId id     = cell->id();
    const auto   stored = stored_rules.find(id);
    if (stored == stored_rules.end())
      {
        generate_level_set_rule(cell, particles, rule);
        stored_rules.emplace(id, StoredRule{rule.cell_specific, rule.owner});
      }
    else
      {
        rule.cell_specific = stored->second.quadrature;
        rule.owner         = stored->second.owner;
        rule.quadrature    = &rule.cell_specific;
        rule.owners_known  = true;
      }
    // A cell the ball only touches (at a point, an edge or within round-off of a face)
    // gets no inside point: it is a fluid cell, with the fluid cells' rule, as its mirror
    // image, which the ball misses by round-off, is.
    if (!rule.has_particle_point())
      {
        rule.kind = CellKind::fluid;
        rule.balls.clear();
        rule.particle = -1;
        rule.quadrature = &regular;
        rule.owner.assign(regular.size(), -1);
      }
  }

  template <int dim>
  void CutCellQuadrature<dim>::append_rules(const BoundingBox<dim> &        box,
                                            const ParticleSet<dim> &        particles,
                                            const std::vector<unsigned int> &balls,
                                            const unsigned int               depth,
                                            std::vector<Point<dim>> &        points,
                                            std::vector<double> &            weights,
                                            std::vector<int> &               owners) const
  {
    // The balls that meet the box, and the images of their centres that do: two images of
    // one ball (a ball across a periodic face, a box across the rest of the period) are
    // separated as two balls are.
    std::vector<unsigned int> meeting;
    std::vector<Point<dim>>   centres;
    for (const unsigned int k : balls)
      {
        const Particle<dim> &p = particles[k];
        auto images = p.centres_near(box, p.bounding_radius() * (1 - Particle<dim>::surface_tolerance));
        // A shape that is not a ball meets fewer boxes than its bounding ball.
        if (!p.shape->is_isotropic())
          images.erase(std::remove_if(images.begin(), images.end(),
                                      [&](const Point<dim> &X) {
                                        return !p.shape->meets(box, X, p.geometry_rotation);
                                      }),
                       images.end());
        if (!images.empty())
          meeting.push_back(k);
        centres.insert(centres.end(), images.begin(), images.end());
      }
    // No ball, or two at the deepest level: the tensor rule, each point owned by the ball
    // that contains it (exact for the Q2 integrands without a ball).
    if (meeting.empty() || (centres.size() > 1 && depth == max_separation_depth))
      {
        const QGauss<dim> gauss(level_set_order);
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            Point<dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = box.lower_bound(d) + box.side_length(d) * gauss.point(q)[d];
            int owner = -1;
            for (const unsigned int k : meeting)
              if (particles[k].contains(x))
                owner = k;
            points.push_back(x);
            weights.push_back(gauss.weight(q) * box.volume());
            owners.push_back(owner);
          }
        return;
      }
    if (centres.size() == 1)
      {
        std::vector<Point<dim>> inside, outside;
        std::vector<double>     inside_weights, outside_weights;
        append_shape_rules(box, centres[0], *particles[meeting[0]].shape,
                           particles[meeting[0]].geometry_rotation, inside, inside_weights,
                           outside, outside_weights);
        points.insert(points.end(), inside.begin(), inside.end());
        weights.insert(weights.end(), inside_weights.begin(), inside_weights.end());
        owners.insert(owners.end(), inside.size(), int(meeting[0]));
        points.insert(points.end(), outside.begin(), outside.end());
        weights.insert(weights.end(), outside_weights.begin(), outside_weights.end());
        owners.insert(owners.end(), outside.size(), -1);
        return;
      }
    for (unsigned int child = 0; child < GeometryInfo<dim>::max_children_per_cell; ++child)
      append_rules(box.child(child), particles, meeting, depth + 1, points, weights, owners);
  }

  template <int dim>
  void CutCellQuadrature<dim>::append_shape_rules(const BoundingBox<dim> &box,
                                                  const Point<dim> &       X,
                                                  const Shape<dim> &       shape,
                                                  const Tensor<2, dim> &   Q,
                                                 std::vector<Point<dim>> &inside_points,
                                                 std::vector<double> &    inside_weights,
                                                 std::vector<Point<dim>> &outside_points,
                                                 std::vector<double> &    outside_weights) const
  {
    const auto        append = [](const Quadrature<dim> &q, std::vector<Point<dim>> &points,
                           std::vector<double> &weights) {
      points.insert(points.end(), q.get_points().begin(), q.get_points().end());
      weights.insert(weights.end(), q.get_weights().begin(), q.get_weights().end());
    };
    // The farthest corner from X.
    double far2 = 0;
    for (unsigned int d = 0; d < dim; ++d)
      far2 += std::pow(std::max(X[d] - box.lower_bound(d), box.upper_bound(d) - X[d]), 2);
    const double inscribed = shape.inscribed_radius();
    if (far2 < inscribed * inscribed)
      {
        // The box lies in the shape: the tensor rule is exact for the Q2 integrands.
        const QGauss<dim> gauss(level_set_order);
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            Point<dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = box.lower_bound(d) + box.side_length(d) * gauss.point(q)[d];
            inside_points.push_back(x);
            inside_weights.push_back(gauss.weight(q) * box.volume());
          }
        return;
      }
    if (shape.has_height_direction(box, X, Q, min_height_slope))
      {
        generator->generate(*shape.level_set(X, Q), box);
        append(generator->get_inside_quadrature(), inside_points, inside_weights);
        append(generator->get_outside_quadrature(), outside_points, outside_weights);
        return;
      }
    // Split where the centre is strictly inside the box (children have it at a corner),
    // else in halves. Children far from X (relative to their size) have a height direction;
    // those next to X shrink until they lie in the ball, after about log2(h sqrt(dim) / R)
    // halvings, so the recursion is shallow. Halves only across the long sides: a thin
    // slab next to X (a centre just inside a cell) split across its thin side too
    // multiplies into 2^dim boxes a level instead of 2^(dim-1) (a 3D ball of R = h/10:
    // 6e5 points in one cell instead of 3e4).
    bool   centre_interior = false;
    double longest = 0;
    for (unsigned int d = 0; d < dim; ++d)
      {
        centre_interior = centre_interior || (X[d] > box.lower_bound(d) && X[d] < box.upper_bound(d));
        longest = std::max(longest, box.side_length(d));
      }
    std::array<std::vector<std::pair<double, double>>, dim> pieces;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const double lo = box.lower_bound(d), hi = box.upper_bound(d);
        const double at = centre_interior ? X[d] : 0.5 * (lo + hi);
        if (at > lo && at < hi && (centre_interior || hi - lo >= 0.5 * longest))
          pieces[d] = {{lo, at}, {at, hi}};
        else
          pieces[d] = {{lo, hi}};
      }
    std::array<unsigned int, dim> index{};
    for (;;)
      {
        Point<dim> lower, upper;
        for (unsigned int d = 0; d < dim; ++d)
          {
            lower[d] = pieces[d][index[d]].first;
            upper[d] = pieces[d][index[d]].second;
          }
        append_shape_rules(BoundingBox<dim>(std::make_pair(lower, upper)), X, shape, Q,
                          inside_points, inside_weights, outside_points, outside_weights);
        unsigned int d = 0;
        while (d < dim && ++index[d] == pieces[d].size())
          index[d++] = 0;
        if (d == dim)
          break;
      }
  }

  template <int dim>
  void CutCellQuadrature<dim>::generate_level_set_rule(
    const typename Triangulation<dim>::cell_iterator &cell, const ParticleSet<dim> &particles,
    CellRule &rule) const
  {
    const BoundingBox<dim>  box = cell->bounding_box();
    std::vector<Point<dim>> points;
    std::vector<double>     weights;
    rule.owner.clear();
    append_rules(box, particles, rule.balls, 0, points, weights, rule.owner);
    // Our cells are axis-aligned boxes, so x = lower + h ⊙ ξ maps the rules to the unit cell
    // and the weights scale with 1/|cell|.
    std::vector<Point<dim>> unit_points(points.size());
    std::vector<double>     unit_weights(points.size());
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        for (unsigned int d = 0; d < dim; ++d)
          unit_points[i][d] = (points[i][d] - box.lower_bound(d)) / box.side_length(d);
        unit_weights[i] = weights[i] / box.volume();
      }
    rule.cell_specific = Quadrature<dim>(unit_points, unit_weights);
    rule.quadrature = &rule.cell_specific;
    rule.owners_known = true;
  }

  template <int dim>
  void CutCellQuadrature<dim>::assign_owners(const std::vector<Point<dim>> &points,
                                             const ParticleSet<dim> &       particles,
                                             CellRule &                     rule) const
  {
    if (rule.owners_known)
      return;
    AssertDimension(points.size(), rule.owner.size());
    for (unsigned int q = 0; q < points.size(); ++q)
      rule.owner[q] = particles.locate(points[q]);
  }

  template <int dim>
  double CutCellQuadrature<dim>::particle_fraction(
    const typename Triangulation<dim>::cell_iterator &cell, const ParticleSet<dim> &particles,
    const Mapping<dim> &mapping) const
  {
    CellRule rule;
    reinit(cell, particles, rule);
    if (rule.kind != CellKind::cut)
      return rule.particle_fraction({});
    const std::vector<Point<dim>> &unit = rule.quadrature->get_points();
    std::vector<Point<dim>>        real(unit.size());
    for (unsigned int q = 0; q < unit.size(); ++q)
      real[q] = mapping.transform_unit_to_real_cell(cell, unit[q]);
    assign_owners(real, particles, rule);
    return rule.particle_fraction(rule.quadrature->get_weights());
  }

  template class CutCellQuadrature<2>;
  template class CutCellQuadrature<3>;
} // namespace fdparticle
