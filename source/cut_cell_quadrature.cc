#include <deal.II/base/function.h>
#include <deal.II/hp/q_collection.h>

#include <fdparticle/cut_cell_quadrature.h>

namespace fdparticle
{
  namespace
  {
    /// ψ(x) = |x − X|² − R²: the ball is ψ < 0. Smooth everywhere (unlike the signed
    /// distance, whose gradient is singular at the centre a small ball's cell contains).
    template <int dim>
    class BallLevelSet : public Function<dim>
    {
    public:
      BallLevelSet(const Point<dim> &center, const double radius)
        : center(center)
        , radius(radius)
      {}
      double value(const Point<dim> &x, const unsigned int = 0) const override
      {
        return (x - center).norm_square() - radius * radius;
      }
      Tensor<1, dim> gradient(const Point<dim> &x, const unsigned int = 0) const override
      {
        return 2.0 * (x - center);
      }
      SymmetricTensor<2, dim> hessian(const Point<dim> &, const unsigned int = 0) const override
      {
        return 2.0 * unit_symmetric_tensor<dim>();
      }

    private:
      const Point<dim> center;
      const double     radius;
    };

  } // namespace

  template <int dim>
  void CutCellQuadrature<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quadrature");
    {
      prm.declare_entry("Cut cells", "gauss", Patterns::Selection("gauss|level set"),
                        "gauss: the seed's rule, 'Gauss points in cut cells' per direction, each "
                        "point counted for the particle that contains it (integrals jump as "
                        "points cross the surface); level set: rules on the parts of the cell "
                        "inside and outside the ball, generated from its level set (Saye 2015), "
                        "smooth in the particle position.");
      prm.declare_entry("Gauss points in cut cells", "7", Patterns::Integer(1, 30),
                        "Gauss points per direction in cells cut by a particle surface; each "
                        "point counts for the particle that contains it (the seed used 7).");
      prm.declare_entry("Level set order", "6", Patterns::Integer(1, 12),
                        "Points of the 1D Gauss rule the level-set rules are built from "
                        "(error ~ h^(2n) for smooth surfaces).");
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
      // The generator keeps a reference to its 1D rules: they must outlive it.
      generator.reset();
      level_set_rules_1d = hp::QCollection<1>(QGauss<1>(level_set_order));
      generator = std::make_unique<NonMatching::QuadratureGenerator<dim>>(level_set_rules_1d);
    }
    prm.leave_subsection();
  }

  template <int dim>
  CellKind CutCellQuadrature<dim>::classify(const typename Triangulation<dim>::cell_iterator &cell,
                                            const ParticleSet<dim> &particles,
                                            int &                   particle) const
  {
    particle = -1;
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const Particle<dim> &p = particles[k];
        if (p.distance_to(cell->bounding_box()) >= p.radius)
          continue;
        particle = k;
        bool all_inside = true;
        for (const unsigned int v : cell->vertex_indices())
          all_inside = all_inside && p.contains(cell->vertex(v));
        return all_inside ? CellKind::inside : CellKind::cut;
      }
    return CellKind::fluid;
  }

  template <int dim>
  void CutCellQuadrature<dim>::reinit(const typename Triangulation<dim>::cell_iterator &cell,
                                      const ParticleSet<dim> &particles,
                                      CellRule &              rule) const
  {
    int particle = -1;
    rule.kind = classify(cell, particles, particle);
    rule.particle = particle;
    rule.quadrature = (rule.kind == CellKind::cut ? &cut : &regular);
    rule.owner.assign(rule.quadrature->size(), rule.kind == CellKind::fluid ? -1 : particle);
    rule.owners_known = (rule.kind != CellKind::cut);
    if (rule.kind != CellKind::cut || cut_method != Method::level_set)
      return;
    // A cell that two balls meet (near contact) keeps the Gauss rule: the level-set rule
    // here describes one ball.
    unsigned int n_meeting = 0;
    for (unsigned int k = 0; k < particles.size(); ++k)
      n_meeting += (particles[k].distance_to(cell->bounding_box()) < particles[k].radius);
    if (n_meeting == 1)
      generate_level_set_rule(cell, particles[particle], particle, rule);
  }

  template <int dim>
  void CutCellQuadrature<dim>::generate_level_set_rule(
    const typename Triangulation<dim>::cell_iterator &cell, const Particle<dim> &particle,
    const int k, CellRule &rule) const
  {
    const BoundingBox<dim> box = cell->bounding_box();
    generator->generate(BallLevelSet<dim>(particle.geometry_center, particle.radius), box);
    // Our cells are axis-aligned boxes, so x = lower + h ⊙ ξ maps the rules to the unit cell
    // and the weights scale with 1/|cell|.
    const Point<dim> lower = box.get_boundary_points().first;
    Tensor<1, dim>   h;
    double           volume = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        h[d] = box.upper_bound(d) - box.lower_bound(d);
        volume *= h[d];
      }
    std::vector<Point<dim>> points;
    std::vector<double>     weights;
    rule.owner.clear();
    for (const bool inside : {true, false})
      {
        const Quadrature<dim> &q =
          inside ? generator->get_inside_quadrature() : generator->get_outside_quadrature();
        for (unsigned int i = 0; i < q.size(); ++i)
          {
            Point<dim> xi;
            for (unsigned int d = 0; d < dim; ++d)
              xi[d] = (q.point(i)[d] - lower[d]) / h[d];
            points.push_back(xi);
            weights.push_back(q.weight(i) / volume);
            rule.owner.push_back(inside ? k : -1);
          }
      }
    rule.cell_specific = Quadrature<dim>(points, weights);
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

  template class CutCellQuadrature<2>;
  template class CutCellQuadrature<3>;
} // namespace fdparticle
