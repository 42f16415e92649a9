#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/full_matrix.h>

#include <fdparticle/fem/introspection.h>
#include <fdparticle/fem/pressure_agglomeration.h>

#include <cmath>
#include <numeric>

namespace fdparticle
{
  template <int dim>
  void PressureAgglomeration<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quadrature");
    prm.declare_entry("Pressure agglomeration", "0", Patterns::Double(0, 1),
                      "f in [0, 1]: a cut cell whose fluid part is at most f of its volume takes "
                      "the linear pressures of its face neighbours with more than f fluid, "
                      "continued into it and weighed by their fluid volumes (constraints), so "
                      "no pressure lives on a fluid sliver alone. 0: every cell has its own "
                      "pressure (doc/method.md §7).");
    prm.leave_subsection();
  }

  template <int dim>
  void PressureAgglomeration<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quadrature");
    max_fluid_fraction = prm.get_double("Pressure agglomeration");
    prm.leave_subsection();
  }

  template <int dim>
  PressureAgglomeration<dim>::PressureAgglomeration(const FESystem<dim> &          fe,
                                                    const Mapping<dim> &           mapping,
                                                    const ParticleSet<dim> &       particles,
                                                    const CutCellQuadrature<dim> &quadrature)
    : fe(fe)
    , mapping(mapping)
    , particles(particles)
    , quadrature(quadrature)
  {}

  template <int dim>
  std::vector<typename PressureAgglomeration<dim>::Link>
  PressureAgglomeration<dim>::links(const DoFHandler<dim> &dof_handler) const
  {
    std::vector<Link> result;
    if (!enabled())
      return result;
    // Fluid parts of the owned and ghost cells, computed where first asked for.
    std::vector<double> fraction(dof_handler.get_triangulation().n_active_cells(), -1.0);
    auto fraction_of = [&](const typename DoFHandler<dim>::active_cell_iterator &cell) {
      double &f = fraction[cell->active_cell_index()];
      if (f < 0)
        f = 1 - quadrature.particle_fraction(cell, particles, mapping);
      return f;
    };

    std::vector<unsigned int> p_local;
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      if (fe.system_to_component_index(i).first == Introspection<dim>::pressure_component)
        p_local.push_back(i);
    const unsigned int                   np = p_local.size();
    const QGauss<dim>                    points(2);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    // Φ_K, the pressure shape functions at the Gauss points of the unit cell, and
    // (Φ_Kᵀ Φ_K)⁻¹: the same for every cell.
    FullMatrix<double> phi_k(points.size(), np), gram(np, np);
    for (unsigned int q = 0; q < points.size(); ++q)
      for (unsigned int a = 0; a < np; ++a)
        phi_k(q, a) = fe.shape_value(p_local[a], points.point(q));
    phi_k.Tmmult(gram, phi_k);
    gram.gauss_jordan();
    // Cells are axis-aligned boxes (doc/method.md §1): unit coordinates by their corners,
    // also for a point outside the cell.
    auto to_unit = [](const auto &cell, const Point<dim> &x) {
      const Point<dim> a = cell->vertex(0), b = cell->vertex(GeometryInfo<dim>::vertices_per_cell - 1);
      Point<dim>       u;
      for (unsigned int d = 0; d < dim; ++d)
        u[d] = (x[d] - a[d]) / (b[d] - a[d]);
      return u;
    };

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        int particle = -1;
        if (quadrature.classify(cell, particles, particle) != CellKind::cut)
          continue;
        const double f = fraction_of(cell);
        if (f > max_fluid_fraction || f >= 1)
          continue;
        // The face neighbours (the finer ones across a refined face too; periodic faces
        // count) whose fluid part is above the threshold, each weighted by its fluid volume:
        // mirror images of a cell take mirror images of its neighbours.
        std::vector<typename DoFHandler<dim>::active_cell_iterator> neighbours;
        std::vector<double>                                         weights;
        // The shift of the cell onto the side of a neighbour across a periodic face (zero
        // across an inner face): the neighbour's polynomial is continued to the image.
        std::vector<Tensor<1, dim>> shifts;
        auto consider = [&](const typename DoFHandler<dim>::active_cell_iterator &n,
                            const unsigned int                                    face) {
          if (n->is_artificial())
            return;
          const double fn = fraction_of(n);
          if (fn > max_fluid_fraction)
            {
              neighbours.push_back(n);
              weights.push_back(fn * n->measure());
              const unsigned int d = face / 2;
              const double       side_n =
                (face % 2 == 0 ? n->vertex(GeometryInfo<dim>::vertices_per_cell - 1) : n->vertex(0))[d];
              Tensor<1, dim> shift;
              shift[d] = side_n - cell->face(face)->center()[d];
              shifts.push_back(shift);
            }
        };
        for (const unsigned int face : cell->face_indices())
          {
            if (cell->at_boundary(face) && !cell->has_periodic_neighbor(face))
              continue;
            const bool periodic  = cell->at_boundary(face);
            const auto neighbour = cell->neighbor_or_periodic_neighbor(face);
            if (neighbour->has_children())
              for (unsigned int s = 0; s < cell->face(face)->n_children(); ++s)
                consider(periodic ? cell->periodic_neighbor_child_on_subface(face, s) :
                                    cell->neighbor_child_on_subface(face, s),
                         face);
            else
              consider(neighbour, face);
          }
        if (neighbours.empty())
          continue;
        const double total = std::accumulate(weights.begin(), weights.end(), 0.0);

        // T_j = (Φ_Kᵀ Φ_K)⁻¹ Φ_Kᵀ Φ_j: neighbour j's linear polynomial continued into the
        // cell, reproduced exactly.
        Link link;
        link.T.reinit(np, np * neighbours.size());
        cell->get_dof_indices(dofs);
        for (const unsigned int i : p_local)
          link.cell_dofs.push_back(dofs[i]);
        for (unsigned int j = 0; j < neighbours.size(); ++j)
          {
            FullMatrix<double> phi_n(points.size(), np), rhs(np, np), T(np, np);
            for (unsigned int q = 0; q < points.size(); ++q)
              {
                const Point<dim> x =
                  to_unit(neighbours[j],
                          mapping.transform_unit_to_real_cell(cell, points.point(q)) + shifts[j]);
                for (unsigned int a = 0; a < np; ++a)
                  phi_n(q, a) = fe.shape_value(p_local[a], x);
              }
            phi_k.Tmmult(rhs, phi_n);
            gram.mmult(T, rhs);
            link.T.add(T, weights[j] / total, 0, np * j);
            neighbours[j]->get_dof_indices(dofs);
            for (const unsigned int i : p_local)
              link.masters.push_back(dofs[i]);
          }
        result.push_back(std::move(link));
      }
    return result;
  }

  template <int dim>
  void PressureAgglomeration<dim>::add_to(const std::vector<Link> &links,
                                          AffineConstraints<double> &constraints)
  {
    for (const Link &link : links)
      for (unsigned int a = 0; a < link.cell_dofs.size(); ++a)
        {
          if (constraints.is_constrained(link.cell_dofs[a]))
            continue;
          constraints.add_line(link.cell_dofs[a]);
          for (unsigned int b = 0; b < link.masters.size(); ++b)
            if (std::abs(link.T(a, b)) > 1e-14)
              constraints.add_entry(link.cell_dofs[a], link.masters[b], link.T(a, b));
        }
  }

  template class PressureAgglomeration<2>;
  template class PressureAgglomeration<3>;
} // namespace fdparticle
