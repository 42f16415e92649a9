#include <fdparticle/cut_cell_quadrature.h>

namespace fdparticle
{
  template <int dim>
  void CutCellQuadrature<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quadrature");
    {
      prm.declare_entry("Gauss points in cut cells", "7", Patterns::Integer(1, 30),
                        "Gauss points per direction in cells cut by a particle surface; each "
                        "point counts for the particle that contains it (the seed used 7).");
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
        // Distance from the centre to the cell's bounding box decides whether they meet.
        const auto box = cell->bounding_box();
        double     dist2 = 0;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double c = p.geometry_center[d];
            const double excess = std::max({box.lower_bound(d) - c, 0.0, c - box.upper_bound(d)});
            dist2 += excess * excess;
          }
        if (dist2 >= p.radius * p.radius)
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
  }

  template <int dim>
  void CutCellQuadrature<dim>::assign_owners(const std::vector<Point<dim>> &points,
                                             const ParticleSet<dim> &       particles,
                                             CellRule &                     rule) const
  {
    if (rule.kind != CellKind::cut)
      return;
    AssertDimension(points.size(), rule.owner.size());
    for (unsigned int q = 0; q < points.size(); ++q)
      rule.owner[q] = particles.locate(points[q]);
  }

  template class CutCellQuadrature<2>;
  template class CutCellQuadrature<3>;
} // namespace fdparticle
