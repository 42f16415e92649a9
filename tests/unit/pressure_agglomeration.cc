// Unit test of fdparticle::PressureAgglomeration<dim>
// (include/fdparticle/fem/pressure_agglomeration.h).
//
// A ball in the unit box, its cut cells refined on one side only, so that nearly covered
// cells have finer, coarser and equal neighbours (and, in a box periodic in x with the ball
// across x = 0, neighbours across the periodic face). The pressure of a linear field p,
// projected cell by cell onto the discontinuous P1 pressure, must be left unchanged by
// the agglomeration's constraints wherever p is linear across the cells a link joins
// (everywhere in a box with walls; in the periodic box, p independent of x): each cell
// takes its neighbours' polynomials continued into it, which are p itself. A field that is
// not linear changes on the agglomerated cells (the links do act), and every link points
// to cells that touch the agglomerated one; across the periodic face, to their image.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/cut_cell_quadrature.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/fem/introspection.h>
#include <fdparticle/fem/pressure_agglomeration.h>
#include <fdparticle/particles/particle_set.h>

#include "unit_check.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  template <int dim>
  void test_links(const bool periodic)
  {
    const unsigned int N = (dim == 2 ? 10 : 6);
    const std::string  centre = periodic ? (dim == 2 ? "0.97, 0.51" : "0.02, 0.51, 0.48") :
                                           (dim == 2 ? "0.47, 0.51" : "0.47, 0.51, 0.48");
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(unit_box_parameters<dim>(N) +
                                (periodic ? "subsection Geometry\n  set Periodic directions = x\nend\n" :
                                            "") +
                                "subsection Particles\n  set Particles = " + centre +
                                " : 0.23 : 2\nend\n"
                                "subsection Quadrature\n  set Pressure agglomeration = 0.3\nend\n");
    Domain<dim>            domain;
    ParticleSet<dim>       particles;
    CutCellQuadrature<dim> quadrature;
    domain.parse_parameters(prm);
    particles.parse_parameters(prm, domain);
    quadrature.parse_parameters(prm);

    parallel::distributed::Triangulation<dim> tria(MPI_COMM_WORLD);
    domain.create_mesh(tria);
    // Refine the cut cells above the ball's centre height: hanging nodes on both sides of
    // the surface.
    const double y_centre = 0.51;
    for (const auto &cell : tria.active_cell_iterators())
      {
        int k = -1;
        if (quadrature.classify(cell, particles, k) == CellKind::cut && cell->center()[1] > y_centre)
          cell->set_refine_flag();
      }
    tria.execute_coarsening_and_refinement();

    const FESystem<dim> fe = Introspection<dim>::finite_element();
    const MappingQ<dim> mapping(1);
    DoFHandler<dim>     dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    PressureAgglomeration<dim> agglomeration(fe, mapping, particles, quadrature);
    agglomeration.parse_parameters(prm);
    const auto links = agglomeration.links(dof_handler);

    const std::string name = std::to_string(dim) + "D" + (periodic ? ", periodic in x" : "");
    std::cout << name << ": " << tria.n_active_cells() << " cells, " << links.size()
              << " agglomerated" << std::endl;
    check(links.size() > 0, name + ": some cut cells are agglomerated");

    // The pressure DoFs of each cell and the cell of each pressure DoF.
    std::vector<unsigned int> p_local;
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      if (fe.system_to_component_index(i).first == Introspection<dim>::pressure_component)
        p_local.push_back(i);
    std::map<types::global_dof_index, typename DoFHandler<dim>::active_cell_iterator> cell_of;
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (const unsigned int i : p_local)
          cell_of[dofs[i]] = cell;
      }

    // Every link: from a cut cell to cells with more fluid, across a face (or a periodic
    // face) of the cell; in the periodic box some link crosses x = 0.
    bool across_period = false, levels_differ = false, neighbours_touch = true;
    for (const auto &link : links)
      {
        const auto cell = cell_of.at(link.cell_dofs[0]);
        for (unsigned int m = 0; m < link.masters.size(); m += p_local.size())
          {
            const auto     n = cell_of.at(link.masters[m]);
            Tensor<1, dim> d = n->center() - cell->center();
            if (periodic && std::abs(d[0]) > 0.5)
              {
                across_period = true;
                d[0] -= std::copysign(1.0, d[0]);
              }
            levels_differ = levels_differ || n->level() != cell->level();
            // Face neighbours: centres half a cell plus half a neighbour apart in one
            // direction, no more than that in the others.
            const double reach = 0.5 * (cell->extent_in_direction(0) + n->extent_in_direction(0));
            neighbours_touch = neighbours_touch && d.norm() <= reach * std::sqrt(double(dim)) + 1e-12;
          }
      }
    check(neighbours_touch, name + ": every master cell touches its agglomerated cell");
    check(levels_differ, name + ": some link joins cells of different refinement levels");
    if (periodic)
      check(across_period, name + ": some link crosses the periodic face");

    // Cell-wise L2 projection of a field onto the pressure space.
    auto project = [&](const std::function<double(const Point<dim> &)> &f) {
      Vector<double>     v(dof_handler.n_dofs());
      const QGauss<dim>  q(3);
      FEValues<dim>      fv(mapping, fe, q, update_values | update_quadrature_points | update_JxW_values);
      const unsigned int np = p_local.size();
      FullMatrix<double> M(np, np);
      Vector<double>     b(np), x(np);
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          fv.reinit(cell);
          M = 0;
          b = 0;
          for (unsigned int k = 0; k < q.size(); ++k)
            for (unsigned int i = 0; i < np; ++i)
              {
                b(i) += f(fv.quadrature_point(k)) * fv.shape_value(p_local[i], k) * fv.JxW(k);
                for (unsigned int j = 0; j < np; ++j)
                  M(i, j) += fv.shape_value(p_local[i], k) * fv.shape_value(p_local[j], k) * fv.JxW(k);
              }
          M.gauss_jordan();
          M.vmult(x, b);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < np; ++i)
            v[dofs[p_local[i]]] = x(i);
        }
      return v;
    };
    AffineConstraints<double> constraints;
    PressureAgglomeration<dim>::add_to(links, constraints);
    constraints.close();
    auto change = [&](const std::function<double(const Point<dim> &)> &f) {
      Vector<double> v = project(f), w = v;
      constraints.distribute(w);
      w -= v;
      return w.linfty_norm() / v.linfty_norm();
    };
    const double linear = change([periodic](const Point<dim> &x) {
      return 0.3 + 1.7 * x[1] - (periodic ? 0.0 : 0.9 * x[0]) + (dim == 3 ? 0.4 * x[dim - 1] : 0.0);
    });
    check(linear < 1e-13, name + ": a linear field is left unchanged",
          "relative change " + std::to_string(linear));
    const double curved = change([](const Point<dim> &x) { return std::sin(7 * x[0]) + x[1] * x[1]; });
    check(curved > 1e-3, name + ": a curved field changes on the agglomerated cells",
          "relative change " + std::to_string(curved));

    // p = x in the periodic box jumps by 1 across x = 0: a cell whose masters lie across
    // the period takes their p continued to its image, x ± 1, so its pressure moves by
    // their share of the weight (between 0 and 1), with the same slope.
    if (periodic)
      {
        Vector<double> v = project([](const Point<dim> &x) { return x[0]; }), w = v;
        constraints.distribute(w);
        bool moved = true;
        for (const auto &link : links)
          {
            const auto cell  = cell_of.at(link.cell_dofs[0]);
            bool       cross = false;
            for (const auto m : link.masters)
              cross = cross || std::abs(cell_of.at(m)->center()[0] - cell->center()[0]) > 0.5;
            if (!cross)
              continue;
            Point<dim> middle;
            for (unsigned int d = 0; d < dim; ++d)
              middle[d] = 0.5;
            double shift = 0;
            for (unsigned int a = 0; a < p_local.size(); ++a)
              shift += (w[link.cell_dofs[a]] - v[link.cell_dofs[a]]) * fe.shape_value(p_local[a], middle);
            moved = moved && std::abs(shift) > 1e-3 && std::abs(shift) <= 1 + 1e-12;
          }
        check(moved, name + ": across the period the masters' pressure is continued to the image");
      }
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
    {
      test_links<2>(false);
      test_links<2>(true);
      test_links<3>(false);
      test_links<3>(true);
    }
  catch (const std::exception &exc)
    {
      std::cerr << "Unexpected exception: " << ParameterTools::one_line_message(exc) << std::endl;
      return 2;
    }
  return unit_check::summary();
}
