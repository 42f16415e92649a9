// Unit test of fdparticle::ParticleRefinement (include/fdparticle/fem/particle_refinement.h):
// the band of refined cells around a ball near a periodic face.
//
// A ball a short distance from the face x = 0 of a box periodic in x is as close to the
// cells at x = 1 as to those at x = 0: the band must reach across the face, and the
// adapted mesh must be the mirror image of itself through the ball's centre (a grid line,
// so the mirror maps the grid to itself), which it is not when the band stops at the face.
// The same box without periodicity keeps the far cells coarse. A ball centred on a vertex
// with a radius of whole cells, moved by round-off, keeps a mesh symmetric about the plane
// it was on. Around an elongated ellipse the finest cells follow its boundary, not its
// bounding or inscribed circles.

#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_tools.h>

#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/fem/particle_refinement.h>
#include <fdparticle/particles/particle_set.h>

#include "unit_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  template <int dim>
  struct Scene
  {
    /// A unit box of N^dim cells, periodic in the directions listed (e.g. "x, z"), with one
    /// ball and the given number of refinement levels around it.
    Scene(const unsigned int N, const std::string &periodic, const std::string &ball,
          const unsigned int levels)
      : tria(MPI_COMM_WORLD)
    {
      ParameterHandler prm;
      declare_all_parameters(prm);
      prm.parse_input_from_string(unit_box_parameters<dim>(N) +
                                  "subsection Geometry\n  set Periodic directions = " + periodic +
                                  "\nend\nsubsection Particles\n  set Particles = " + ball +
                                  "\nend\nsubsection Refinement\n  set Particle refinement levels = " +
                                  std::to_string(levels) + "\nend\n");
      domain.parse_parameters(prm);
      particles.parse_parameters(prm, domain);
      refinement.parse_parameters(prm);
      domain.create_mesh(tria);
    }

    /// Whether the active cell whose box is [lower, upper] lies in the band.
    bool cell_in_band(const Point<dim> &lower, const Point<dim> &upper) const
    {
      const Point<dim> center = 0.5 * (lower + upper);
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->center().distance(center) < 1e-12)
          return refinement.in_band(cell, particles);
      check(false, "the test's cell exists", "");
      return false;
    }

    /// The passes Simulation makes at the start (one more than levels: the last coarsens).
    void adapt()
    {
      for (unsigned int pass = 0; pass <= refinement.levels(); ++pass)
        if (refinement.mark(tria, particles, 0))
          tria.execute_coarsening_and_refinement();
    }

    Domain<dim>                               domain;
    ParticleSet<dim>                          particles;
    ParticleRefinement<dim>                   refinement;
    parallel::distributed::Triangulation<dim> tria;
  };

  /// Key of a point for a map: coordinates rounded to 1e-9 (the cells here are ≥ 1/32).
  template <int dim>
  std::array<long, dim> key(const Point<dim> &x)
  {
    std::array<long, dim> k;
    for (unsigned int d = 0; d < dim; ++d)
      k[d] = std::lround(x[d] * 1e9);
    return k;
  }

  /// Active cells without a mirror image (through the plane x = x0, wrapped into the
  /// periodic unit interval) of the same level.
  template <int dim>
  unsigned int cells_without_mirror_image(const Triangulation<dim> &tria, const double x0)
  {
    std::map<std::array<long, dim>, int> level_of;
    for (const auto &cell : tria.active_cell_iterators())
      level_of[key(cell->center())] = cell->level();
    unsigned int n = 0;
    for (const auto &cell : tria.active_cell_iterators())
      {
        Point<dim> image = cell->center();
        image[0] = 2 * x0 - image[0];
        image[0] -= std::floor(image[0]);
        const auto it = level_of.find(key(image));
        n += (it == level_of.end() || it->second != cell->level());
      }
    return n;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  std::cout << "2D: ball at x = 0.125, R = 0.1, on an 8 x 8 unit box (h = 1/8)" << std::endl;
  {
    // The ball's surface is 0.025 from the face x = 0; the cell [7/8, 1] x [3/8, 1/2] is
    // that far plus nothing from it across the periodic face, 0.775 without periodicity.
    const std::string ball = "0.125, 0.5 : 0.1 : 1";
    const Point<2>    far_lower(0.875, 0.375), far_upper(1, 0.5);
    Scene<2>          walled(8, "", ball, 2);
    Scene<2>          periodic(8, "x", ball, 2);
    check(!walled.cell_in_band(far_lower, far_upper),
          "between walls the cell at the far face is outside the band");
    check(periodic.cell_in_band(far_lower, far_upper),
          "periodic in x the cell across the face is inside the band");
    check(!periodic.cell_in_band(Point<2>(0.5, 0.375), Point<2>(0.625, 0.5)),
          "periodic in x a cell in the middle of the box is outside the band");

    periodic.adapt();
    walled.adapt();
    const unsigned int n_periodic = cells_without_mirror_image(periodic.tria, 0.125);
    check(n_periodic == 0,
          "periodic: the adapted mesh is its own mirror image through the ball's centre",
          std::to_string(n_periodic) + " of " + std::to_string(periodic.tria.n_active_cells()) +
            " cells have none");
    check(periodic.tria.n_active_cells() > walled.tria.n_active_cells(),
          "periodic: the band across the face adds cells",
          std::to_string(periodic.tria.n_active_cells()) + " vs " +
            std::to_string(walled.tria.n_active_cells()));
  }

  std::cout << "3D: ball near the edge x = z = 0 of a 4^3 unit box periodic in x and z" << std::endl;
  {
    // The cell [3/4, 1] x [1/4, 1/2] x [3/4, 1] is near the ball only through its image
    // shifted in x and z at once.
    const std::string ball = "0.1, 0.4, 0.1 : 0.08 : 1";
    const Point<3>    corner_lower(0.75, 0.25, 0.75), corner_upper(1, 0.5, 1);
    Scene<3>          both(4, "x, z", ball, 1);
    Scene<3>          x_only(4, "x", ball, 1);
    check(both.cell_in_band(corner_lower, corner_upper),
          "periodic in x and z the cell across the edge is inside the band");
    check(!x_only.cell_in_band(corner_lower, corner_upper),
          "periodic in x only the cell across the edge is outside the band");
    check(x_only.cell_in_band(Point<3>(0.75, 0.25, 0), Point<3>(1, 0.5, 0.25)),
          "periodic in x only the cell across the face x = 0 is inside the band");
  }

  std::cout << "3D: ball centred on a vertex, R = 2 finest cells, moved by round-off" << std::endl;
  {
    // On 6^3 cells refined twice (h = 1/24), R = 2h: the band's edges R + h_K fall on mesh
    // planes. A centre moved off x = 0.5 by 2e-11 (the round-off of some twenty steps of a
    // symmetric scene, prm/dkt3d.prm) must leave the mesh its own mirror image through
    // x = 0.5; with a slack of 1e-10 R (8e-12) one side lost a row of refined cells.
    Scene<3> moved(6, "", "0.50000000002, 0.5, 0.5 : 0.0833333333333333 : 1", 2);
    moved.adapt();
    const unsigned int n = cells_without_mirror_image(moved.tria, 0.5);
    check(n == 0, "the adapted mesh is its own mirror image through x = 0.5",
          std::to_string(n) + " of " + std::to_string(moved.tria.n_active_cells()) +
            " cells have none");
  }
  std::cout << "2D: an elongated ellipse, turned" << std::endl;
  {
    // On 16^2 cells refined twice around an ellipse 0.3 x 0.12 turned by 30 degrees: the
    // cells its boundary crosses are refined to the finest level, and a finest cell lies
    // within 2.5 times its parent's size h of the boundary: its parent was in the band
    // (width 1), which reaches √2 h outside (the box grown by h) and a/b h inside (the
    // ellipse shrunk about its centre by 1 − h/b), not deep inside nor off the ellipse's
    // sides within its bounding circle (0.18 from it). The boundary is sampled at 4000
    // points.
    Scene<2> ellipse(16, "", "0.5, 0.5 : ellipse 0.3, 0.12, 30 : 1", 2);
    ellipse.adapt();
    std::vector<Point<2>> boundary;
    const double          t = 30 * numbers::PI / 180;
    for (unsigned int k = 0; k < 4000; ++k)
      {
        const double s = 2 * numbers::PI * k / 4000;
        const double x = 0.3 * std::cos(s), y = 0.12 * std::sin(s);
        boundary.emplace_back(0.5 + std::cos(t) * x - std::sin(t) * y,
                              0.5 + std::sin(t) * x + std::cos(t) * y);
      }
    unsigned int n_cut_coarse = 0, n_far = 0, n_finest = 0;
    for (const auto &cell : ellipse.tria.active_cell_iterators())
      {
        const BoundingBox<2> box = cell->bounding_box();
        double               distance = std::numeric_limits<double>::max();
        for (const Point<2> &x : boundary)
          {
            double d2 = 0;
            for (unsigned int d = 0; d < 2; ++d)
              d2 += std::pow(std::max({box.lower_bound(d) - x[d], 0.0, x[d] - box.upper_bound(d)}), 2);
            distance = std::min(distance, std::sqrt(d2));
          }
        const double parent_h = 2 * cell->diameter() / std::sqrt(2.0);
        if (cell->level() == 2)
          {
            ++n_finest;
            n_far += (distance > 2.5 * parent_h * (1 + 1e-3));
          }
        else
          n_cut_coarse += (distance == 0);
      }
    check(n_cut_coarse == 0, "the cells the boundary crosses are at the finest level",
          std::to_string(n_cut_coarse) + " are not");
    check(n_far == 0, "the finest cells lie within 2.5 parent sizes of the boundary",
          std::to_string(n_far) + " of " + std::to_string(n_finest) + " do not");
  }
  return summary();
}
