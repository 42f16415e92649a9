// Unit test of the particle input at scale, in 2D and 3D: the particle file
// (include/fdparticle/particles/particle_file.h) read through ParticleSet, and the random
// placement (random_packing.h).
//
// The file's particles are compared with the values written into it, line by line; its
// errors must name the line. The random balls are checked by the comparison of all pairs
// with the nearest periodic image found by trying every shift by a box length, against
// the walls and the sub-box, for the radius range, and for the same balls from the same
// seed. The program prints each check and returns 1 if any fails.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/particles/contact_geometry.h>
#include <fdparticle/particles/particle_set.h>

#include "unit_check.h"

#include <cstdio>
#include <fstream>
#include <limits>
#include <random>
#include <string>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  const std::string csv_name = "unit_particle_input.csv";

  /// The scene: box [0,1] x [0,1.5] (x [0,1.2]), 'particles' is the body of subsection
  /// Particles. Returns the error message, or "" if the particles were accepted.
  template <int dim>
  std::string parse(const std::string &periodic, const std::string &particles,
                    ParticleSet<dim> &set, Domain<dim> &domain)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    try
      {
        prm.parse_input_from_string(
          "set Dimension = " + std::to_string(dim) + "\nsubsection Geometry\n" +
          "  set Lower corner = " + (dim == 2 ? "0, 0" : "0, 0, 0") +
          "\n  set Upper corner = " + (dim == 2 ? "1, 1.5" : "1, 1.5, 1.2") +
          "\n  set Subdivisions = " + (dim == 2 ? "4, 6" : "4, 6, 5") +
          "\n  set Periodic directions = " + periodic + "\nend\nsubsection Particles\n" +
          particles + "\nend\n");
        domain.parse_parameters(prm);
        set.parse_parameters(prm, domain);
      }
    catch (const std::exception &exc)
      {
        return ParameterTools::one_line_message(exc);
      }
    return "";
  }

  bool contains(const std::string &text, const std::string &part)
  {
    return text.find(part) != std::string::npos;
  }

  void write(const std::string &text)
  {
    std::ofstream(csv_name) << text;
  }

  template <int dim>
  void test_file()
  {
    std::cout << dim << "D particle file" << std::endl;
    // A comment, a header, a blank line, then a free ellipse or ellipsoid, fixed (padded
    // with empty columns as a spreadsheet writes them) and prescribed balls.
    const std::string three = (dim == 2 ? "" : ", 0.6");
    const std::string shape = (dim == 2 ? "ellipse 0.15 0.05 30" : "ellipsoid 0.15 0.05 0.07 0 0 1 30");
    write("# three particles\nx, y" + std::string(dim == 3 ? ", z" : "") +
          ", radius, density, motion\n\n0.3, 0.4" + three + ", " + shape + ", 2\n" + "0.7, 0.4" +
          three + ", 0.12, 3, fixed,,,\n" + "0.5, 1.1" + three + ", 0.08, 1.5, prescribed, 0.5, -1" +
          (dim == 2 ? ", 2" : ", 0.25, 1, 2, 3") + "\n");
    ParticleSet<dim> set;
    Domain<dim>      domain;
    const std::string error = parse<dim>("", "set Particles = 0.5, 0.75" + three +
                                               " : 0.05 : 4\nset Particle file = " + csv_name,
                                         set, domain);
    check(error.empty(), "file accepted", error);
    if (!error.empty())
      return;
    check(set.size() == 4, "the list's particle, then the file's three");
    check_close(set[0].bounding_radius(), 0.05, 0, "the list's particle comes first");
    check_close(set[1].position[1], 0.4, 0, "line 4: y");
    check(set[1].shape->name() == (dim == 2 ? "ellipse" : "ellipsoid") &&
            set[1].bounding_radius() == 0.15 &&
            std::abs(Eigen::AngleAxisd(set[1].orientation).angle() - numbers::PI / 6) < 1e-14,
          "line 4: the shape, its semi-axes and its turn by 30 degrees");
    check_close(set[2].bounding_radius(), 0.12, 0, "line 5: radius");
    check_close(set[2].density, 3.0, 0, "line 5: density");
    check(set[1].motion == ParticleMotion::free && set[2].motion == ParticleMotion::fixed &&
            set[3].motion == ParticleMotion::prescribed,
          "motions free (default), fixed, prescribed");
    check_close(set[3].velocity[1], -1.0, 0, "line 6: prescribed vy");
    check_close(set[3].omega[2], dim == 2 ? 2.0 : 3.0, 0, "line 6: prescribed w_z");
    check(set.n_unknowns() == 2 * RigidBody<dim>::n_unknowns, "two free particles' unknowns");

    // Errors name the file's line.
    const std::string ok = "0.3, 0.4" + three + ", 0.1, 2\n";
    const std::vector<std::pair<std::string, std::string>> bad = {
      {ok + "# c\n0.7, x" + three + ", 0.1, 2\n", "line 3) centre"},
      {ok + ok.substr(0, ok.size() - 3) + "\n", "line 2)': '"},
      {ok + "0.7, 0.4" + three + ", 0.1, 2, rolling\n", "line 2)': motion 'rolling'"},
      {ok + "0.7, 0.4" + three + ", 0.1, 2, prescribed\n", "line 2)': 'prescribed' needs"},
      {ok + "0.7, 0.4" + three + ", -0.1, 2\n", "line 2)': the radius must be positive"},
      {ok + "0.7, 0.4" + three + (dim == 2 ? ", ellipse 0.1 -0.05, 2\n" : ", ellipsoid 0.1 0.05 0, 2\n"),
       "line 2)': the semi-axes of an"},
      {"# nothing\n", "lists no particle"},
      {ok + "0.35, 0.4" + three + ", 0.1, 2\n", "Particles 0 and 1 overlap"}};
    // A 3D file in a 2D scene: its z column shifts the radius, density into motion's place.
    if (dim == 2)
      {
        write(ok + "0.7, 0.4, 0.5, 0.1, 2\n");
        ParticleSet<dim>  s;
        const std::string e = parse<dim>("", "set Particle file = " + csv_name, s, domain);
        check(contains(e, "line 2)': '0.7, 0.4, 0.5, 0.1, 2' has a number where the motion") &&
                contains(e, "3D particle file"),
              "a 3D line in a 2D scene is named as one", e.substr(0, 300));
      }
    for (const auto &[text, expected] : bad)
      {
        write(text);
        ParticleSet<dim> s;
        const std::string e = parse<dim>("", "set Particle file = " + csv_name, s, domain);
        check(contains(e, expected), "error names it: " + expected, e.substr(0, 300));
      }
    std::remove(csv_name.c_str());
    ParticleSet<dim>  s;
    const std::string e = parse<dim>("", "set Particle file = " + csv_name, s, domain);
    check(contains(e, "cannot read 'unit_particle_input.csv'"), "a missing file is named",
          e.substr(0, 300));
  }

  /// The smallest gap of all pairs (the nearest periodic image found by trying every
  /// shift), and how many pairs' bounding balls come closer than `closer`.
  template <int dim>
  double smallest_gap(const ParticleSet<dim> &set, const Domain<dim> &domain,
                      const double closer = 0, unsigned int *n_closer = nullptr)
  {
    double smallest = std::numeric_limits<double>::max();
    for (unsigned int i = 0; i < set.size(); ++i)
      for (unsigned int j = i + 1; j < set.size(); ++j)
        {
          const Tensor<1, dim> offset = nearest_image_offset(set[i].position, set[j].position, domain);
          const double ball_gap = offset.norm() - set[i].bounding_radius() - set[j].bounding_radius();
          if (n_closer != nullptr && ball_gap < closer)
            ++*n_closer;
          smallest = std::min(smallest, ContactGeometry<dim>::pair(set[i], set[j], offset).gap);
        }
    return smallest;
  }

  /// Random particles of the given shape ('ball', or the ratios 'ellipse a, b' /
  /// 'ellipsoid a, b, c'); twenty times as many must jam unless the shape is too thin to
  /// (jams = false).
  template <int dim>
  void test_random(const std::string &periodic, const std::string &shape = "ball",
                   const bool jams = true)
  {
    std::cout << dim << "D random particles (" << shape << "), periodic directions '"
              << periodic << "'" << std::endl;
    const bool         balls = (shape == "ball");
    const unsigned int count = (dim == 2 ? 40 : 150);
    const double       gap = 0.02, r_min = 0.03, r_max = 0.05;
    const std::string  three = (dim == 2 ? "" : ", 0.6");
    const auto random = [&](const unsigned int seed, const unsigned int n) {
      return "set Particles = 0.5, 1.2" + three + " : 0.1 : 2\nsubsection Random particles\n"
             "  set Count = " + std::to_string(n) + "\n  set Shape = " + shape +
             "\n  set Radius = " + std::to_string(r_min) +
             ", " + std::to_string(r_max) + "\n  set Density = 1.5\n  set Minimum gap = " +
             std::to_string(gap) + "\n  set Lower corner = " + (dim == 2 ? "0, 0.5" : "0, 0.5, 0") +
             "\n  set Seed = " + std::to_string(seed) + "\nend";
    };
    ParticleSet<dim> set, same, other;
    Domain<dim>      domain;
    std::string      error = parse<dim>(periodic, random(7, count), set, domain);
    check(error.empty(), "placed", error.substr(0, 300));
    if (!error.empty())
      return;
    check(set.size() == count + 1, "the list's ball and " + std::to_string(count) + " random ones");
    unsigned int n_closer = 0;
    const double smallest = smallest_gap(set, domain, gap, &n_closer);
    check(smallest >= gap * (1 - 1e-9),
          "no two particles closer than the minimum gap (all pairs, nearest periodic image)",
          sci(smallest));
    if (!balls)
      check(n_closer > 0, "the true gap, not the bounding balls', is kept",
            std::to_string(n_closer) + " pairs of bounding balls closer than the gap");
    bool         in_sub_box = true, off_walls = true, radii = true, free = true, shapes = true;
    unsigned int n_crossing = 0;
    // 2D: the mean of (cos 2θ, sin 2θ) of the a axes; 3D: of a aᵀ − I/3. Both vanish for
    // orientations uniform over all rotations.
    Tensor<2, 3> spread;
    for (unsigned int k = 1; k < set.size(); ++k)
      {
        const Particle<dim> &p = set[k];
        radii = radii && p.bounding_radius() >= r_min && p.bounding_radius() <= r_max && p.density == 1.5;
        free = free && p.motion == ParticleMotion::free;
        shapes = shapes && p.shape->name() == (dim == 2 ? (balls ? "disk" : "ellipse") : (balls ? "sphere" : "ellipsoid"));
        Tensor<1, dim> up;
        up[1] = 1;
        in_sub_box = in_sub_box && p.position[1] - p.extent(-up) >= 0.5;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double lower = domain.lower_corner()[d], upper = domain.upper_corner()[d];
            Tensor<1, dim> e;
            e[d] = 1;
            // The sub-box spans the periodic directions: centres anywhere, particles across.
            if (domain.is_periodic(d))
              {
                off_walls = off_walls && p.position[d] >= lower && p.position[d] < upper;
                n_crossing += (p.position[d] - p.bounding_radius() < lower || p.position[d] + p.bounding_radius() > upper);
              }
            else
              off_walls = off_walls && p.position[d] - p.extent(-e) >= lower + gap * (1 - 1e-9) &&
                          p.position[d] + p.extent(e) <= upper - gap * (1 - 1e-9);
          }
        const Tensor<2, 3> Q = RigidBody<dim>::template rotation_matrix<3>(p.orientation);
        if (dim == 2)
          {
            const double c = Q[0][0], s = Q[1][0]; // the a axis
            spread[0][0] += (c * c - s * s) / count;
            spread[0][1] += 2 * c * s / count;
          }
        else
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int b = 0; b < 3; ++b)
              spread[a][b] += (Q[a][0] * Q[b][0] - (a == b ? 1.0 / 3 : 0.0)) / count;
      }
    check(radii, "sizes (bounding radii) in [min, max], density as given");
    check(free, "random particles are free");
    check(shapes, "of the shape asked");
    check(in_sub_box, "particles inside the sub-box");
    check(off_walls, "walls kept at the minimum gap (true extents), centres in the box");
    if (!periodic.empty())
      check(n_crossing > 0, "particles cross the periodic faces",
            std::to_string(n_crossing) + " crossings");
    if (!balls)
      // Uniform orientations: each mean is of order 1/√count (0.16 in 2D, 0.08 in 3D);
      // all particles turned alike would give 1 (2D) or 2/3 (3D).
      check(spread.norm() < 3 / std::sqrt(count), "orientations spread over all rotations",
            "spread " + sci(spread.norm()));
    parse<dim>(periodic, random(7, count), same, domain);
    parse<dim>(periodic, random(8, count), other, domain);
    double same_difference = 0, other_difference = 0;
    for (unsigned int k = 1; k < set.size(); ++k)
      {
        same_difference += (set[k].position - same[k].position).norm() +
                           set[k].orientation.angularDistance(same[k].orientation);
        other_difference += (set[k].position - other[k].position).norm();
      }
    check(same_difference == 0, "the same seed gives the same particles");
    check(other_difference > 0, "another seed gives other particles");
    if (!balls)
      {
        if (!jams)
          return;
        ParticleSet<dim> jammed;
        error = parse<dim>(periodic, random(7, 20 * count), jammed, domain);
        check(contains(error, "jams near"), "an impossible packing is refused with its fraction",
              error.substr(0, 300));
        return;
      }

    // The cell-to-particles index against trying every ball: random boxes from a tenth of
    // a ball to a whole coarse region, and random points.
    std::mt19937                           generator(11 + dim);
    std::uniform_real_distribution<double> uniform(0, 1);
    bool same_meeting = true, same_owner = true;
    unsigned int n_met = 0;
    for (unsigned int trial = 0; trial < 2000; ++trial)
      {
        Point<dim> a, b;
        const double size = std::pow(10.0, -2 + 2.5 * uniform(generator));
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double l = domain.lower_corner()[d], u = domain.upper_corner()[d];
            a[d] = l + (u - l) * uniform(generator);
            b[d] = std::min(u, a[d] + size);
          }
        const BoundingBox<dim>    box({a, b});
        std::vector<unsigned int> expected;
        for (unsigned int k = 0; k < set.size(); ++k)
          if (set[k].distance_to(box) < set[k].bounding_radius())
            expected.push_back(k);
        same_meeting = same_meeting && set.meeting(box) == expected;
        n_met += expected.size();
        int owner = -1;
        for (unsigned int k = 0; k < set.size() && owner < 0; ++k)
          if (set[k].contains(a))
            owner = k;
        same_owner = same_owner && set.locate(a) == owner;
      }
    check(same_meeting && n_met > 100, "meeting(box) lists the balls that meet the box (" +
                                          std::to_string(n_met) + " in 2000 boxes)");
    check(same_owner, "locate(x) finds the ball containing x");

    ParticleSet<dim> jammed;
    error = parse<dim>(periodic, random(7, 20 * count), jammed, domain);
    check(contains(error, "jams near"), "an impossible packing is refused with its fraction",
          error.substr(0, 300));
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  test_file<2>();
  test_file<3>();
  test_random<2>("");
  test_random<2>("x");
  test_random<3>("x, z");
  test_random<2>("", "ellipse 2, 1");
  test_random<2>("x", "ellipse 1, 3");
  test_random<3>("x, z", "ellipsoid 2, 1, 1");
  test_random<3>("", "ellipsoid 1, 0.5, 3", false);
  // Shapes that random placement refuses, each named.
  for (const auto &[text, expected] :
       std::vector<std::pair<std::string, std::string>>{
         {"0.1", "Random particles/Shape' is 'ball' or 'ellipse a, b'"},
         {"ellipse 2, 1, 30", "takes no angle"},
         {"ellipse 2, 0", "semi-ax"},
         {"ellipsoid 2, 1, 1", "2D scene has no ellipsoid"}})
    {
      ParticleSet<2>    set;
      Domain<2>         domain;
      const std::string e =
        parse<2>("", "subsection Random particles\n  set Count = 3\n  set Shape = " + text + "\nend",
                 set, domain);
      check(contains(e, expected), "refused: " + text, e.substr(0, 300));
    }
  return summary();
}
