// Unit test of parameter reading: fdparticle::declare_all_parameters (simulation.h) into a
// ParameterHandler, then Domain<dim>, Fluid<dim> and ParticleSet<dim>::parse_parameters as
// Simulation does. Good input must give the numbers written in it; each bad input must
// throw, and the one-line message (ParameterTools::one_line_message) must contain the key
// phrase of the check that rejects it (wording taken from source/*.cc).

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/fem/domain.h>
#include <fdparticle/base/fluid.h>
#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/particle_set.h>
#include <fdparticle/core/simulation.h>

#include "unit_check.h"

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{

  void check_close(const double value, const double expected, const std::string &what)
  {
    std::ostringstream s;
    s.precision(17);
    s << "got " << value << ", expected " << expected;
    check(std::abs(value - expected) <= 1e-14 * std::max(1.0, std::abs(expected)), what, s.str());
  }

  template <int dim>
  void check_close(const Tensor<1, dim> &value, const Tensor<1, dim> &expected,
                   const std::string &what)
  {
    std::ostringstream s;
    s.precision(17);
    s << "got (" << value << "), expected (" << expected << ")";
    check((value - expected).norm() <= 1e-14 * std::max(1.0, expected.norm()), what, s.str());
  }

  const std::string base_2d = R"(
set Dimension = 2
set Gravity = 0, -9.81
subsection Geometry
  set Lower corner = -1, 0
  set Upper corner = 1, 4
  set Subdivisions = 4, 8
  set Global refinements = 2
  set Periodic directions =
end
subsection Boundary conditions
  set Wall velocities = y+: 1.5, 0
end
subsection Fluid
  set Density = 1000
  set Viscosity = 0.01
  set Body force = 0.5, 0
end
subsection Particles
  set Particles = 0, 1 : 0.25 : 1200 ; 0.5, 3 : 0.125 : 800 : fixed
end
)";

  const std::string base_3d = R"(
set Dimension = 3
set Gravity = 0, 0, -9.81
subsection Geometry
  set Lower corner = 0, 0, 0
  set Upper corner = 1, 2, 3
  set Subdivisions = 2, 4, 6
  set Global refinements = 0
  set Periodic directions = x, z
end
subsection Boundary conditions
  set Wall velocities = y-: 0.5, 0, -0.25
end
subsection Fluid
  set Density = 2
  set Viscosity = 3e-2
  set Body force = 1, 0, 0
end
subsection Particles
  set Particles = 0.5, 1, 1.5 : 0.2 : 2 ; 0.5, 0.5, 0.5 : 0.1 : 3 : free
  set Angular velocity closure = kinematic
end
)";

  /// "subsection A\n set B = v\n end\n" for the path "A/B" (or "set B = v" at top level).
  std::string override_entry(const std::string &path, const std::string &value)
  {
    const auto slash = path.find('/');
    if (slash == std::string::npos)
      return "set " + path + " = " + value + "\n";
    return "subsection " + path.substr(0, slash) + "\n  set " + path.substr(slash + 1) + " = " +
           value + "\nend\n";
  }

  template <int dim>
  struct Parsed
  {
    Domain<dim>      domain;
    Fluid<dim>       fluid;
    ParticleSet<dim> particles;
    unsigned int     dimension = 0;
  };

  /// Parse like Simulation's constructor does.
  template <int dim>
  void parse(const std::string &text, Parsed<dim> &out)
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(text);
    out.dimension = prm.get_integer("Dimension");
    out.domain.parse_parameters(prm);
    out.fluid.parse_parameters(prm);
    out.particles.parse_parameters(prm, out.domain);
  }

  /// The base input of dimension dim with one entry changed must throw with 'phrase'.
  template <int dim>
  void check_rejected(const std::string &path, const std::string &value, const std::string &phrase)
  {
    const std::string what =
      std::to_string(dim) + "D " + path + " = '" + value + "' -> '..." + phrase + "...'";
    Parsed<dim> parsed;
    try
      {
        parse<dim>((dim == 2 ? base_2d : base_3d) + override_entry(path, value), parsed);
      }
    catch (const std::exception &exc)
      {
        const std::string m = ParameterTools::one_line_message(exc);
        const bool one_line = m.find('\n') == std::string::npos &&
                              m.find("An error occurred") == std::string::npos &&
                              m.find("Stacktrace") == std::string::npos &&
                              m.find("Additional information") == std::string::npos &&
                              m.find("------") == std::string::npos;
        check(m.find(phrase) != std::string::npos && one_line, what, "message: " + m);
        std::cout << "          (" << m << ")" << std::endl;
        return;
      }
    check(false, what, "no exception");
  }

  void test_good_2d()
  {
    std::cout << "Good 2D input" << std::endl;
    Parsed<2> p;
    parse<2>(base_2d, p);
    check(p.dimension == 2, "Dimension == 2");
    const Domain<2> &d = p.domain;
    check_close(Tensor<1, 2>(d.lower_corner()), Tensor<1, 2>({-1, 0}), "lower corner (-1, 0)");
    check_close(Tensor<1, 2>(d.upper_corner()), Tensor<1, 2>({1, 4}), "upper corner (1, 4)");
    check_close(d.volume(), 8.0, "volume 2 x 4 = 8");
    // min(2/4, 4/8) / 2^2
    check_close(d.base_cell_size(), 0.125, "base_cell_size = min(2/4, 4/8) / 4");
    for (unsigned int dir = 0; dir < 2; ++dir)
      check(!d.is_periodic(dir), "direction " + std::to_string(dir) + " not periodic");
    for (types::boundary_id f = 0; f < 4; ++f)
      {
        check(d.is_wall(f), "face " + Domain<2>::face_name(f) + " is a wall");
        check_close(d.wall_velocity(f), f == 3 ? Tensor<1, 2>({1.5, 0}) : Tensor<1, 2>(),
                    "wall velocity of " + Domain<2>::face_name(f));
      }
    check(Domain<2>::face_name(0) == "x-" && Domain<2>::face_name(3) == "y+", "face names");
    // Neumann modes of the 2 x 4 box: k = pi (m/2, n/4), i.e. pi/4 (0, 1), pi/2 (0, 2) and
    // (1, 0), 1.76 (1, 1).
    check(d.count_modes_below(0.7, 100) == 0, "no Laplace mode below 0.7 < pi/4");
    check(d.count_modes_below(1.5, 100) == 1, "one Laplace mode below 1.5: pi/4");
    check(d.count_modes_below(1.6, 100) == 3, "three Laplace modes below 1.6: pi/4, pi/2 twice");

    check_close(p.fluid.density, 1000.0, "fluid density 1000");
    check_close(p.fluid.viscosity, 0.01, "viscosity 0.01");
    check(p.fluid.convection, "convection default true");
    check_close(p.fluid.gravity, Tensor<1, 2>({0, -9.81}), "gravity (0, -9.81)");
    check_close(p.fluid.body_force, Tensor<1, 2>({0.5, 0}), "body force (0.5, 0)");
    check_close(p.fluid.hydrostatic_gradient(), Tensor<1, 2>({0.5, -9810}),
                "rho g + f = (0.5, -9810)");

    const ParticleSet<2> &ps = p.particles;
    check(ps.size() == 2, "2 particles");
    if (ps.size() == 2)
      {
        check_close(Tensor<1, 2>(ps[0].position), Tensor<1, 2>({0, 1}), "particle 1 centre");
        check_close(ps[0].bounding_radius(), 0.25, "particle 1 radius");
        check_close(ps[0].density, 1200.0, "particle 1 density");
        check(ps[0].motion == ParticleMotion::free, "particle 1 free (default)");
        check(ps[0].first_unknown == 0, "particle 1 unknowns start at 0");
        check_close(Tensor<1, 2>(ps[1].position), Tensor<1, 2>({0.5, 3}), "particle 2 centre");
        check_close(ps[1].bounding_radius(), 0.125, "particle 2 radius");
        check_close(ps[1].density, 800.0, "particle 2 density");
        check(ps[1].motion == ParticleMotion::fixed, "particle 2 fixed");
        check(ps[1].first_unknown == numbers::invalid_unsigned_int, "particle 2 has no unknowns");
        check(ps[1].id == 1, "particle 2 id 1");
        check(ps[0].geometry_center == ps[0].position && ps[0].position_old == ps[0].position,
              "geometry centre and old position start at the centre");
        check(ps[0].velocity.norm() == 0 && ps[0].omega.norm() == 0, "particle starts at rest");
      }
    check(ps.n_unknowns() == 3, "particle block: 3 unknowns (one free 2D particle)");
    check(ps.closure() == AngularVelocityClosure::torque_balance, "closure default torque balance");
  }

  void test_good_3d()
  {
    std::cout << "Good 3D input" << std::endl;
    Parsed<3> p;
    parse<3>(base_3d, p);
    check(p.dimension == 3, "Dimension == 3");
    const Domain<3> &d = p.domain;
    check_close(Tensor<1, 3>(d.upper_corner()), Tensor<1, 3>({1, 2, 3}), "upper corner (1, 2, 3)");
    check_close(d.volume(), 6.0, "volume 6");
    check_close(d.base_cell_size(), 0.5, "base_cell_size 0.5");
    check(d.is_periodic(0) && !d.is_periodic(1) && d.is_periodic(2), "periodic in x and z only");
    const bool walls[6] = {false, false, true, true, false, false};
    for (types::boundary_id f = 0; f < 6; ++f)
      check(d.is_wall(f) == walls[f],
            "face " + Domain<3>::face_name(f) + (walls[f] ? " is a wall" : " is no wall"));
    check_close(d.wall_velocity(2), Tensor<1, 3>({0.5, 0, -0.25}), "wall velocity of y-");
    check_close(d.wall_velocity(3), Tensor<1, 3>(), "wall y+ at rest");
    // Laplace modes of the box periodic in x (length 1) and z (3), walls in y (2):
    // k = (2 pi l, pi m/2, 2 pi n/3), l and n of either sign: pi/2 (m = 1), 2.09 (n = +-1),
    // 2.62 (m = 1, n = +-1), pi (m = 2), then 3.78 (m = 2, n = +-1).
    check(d.count_modes_below(2.0, 100) == 1, "one Laplace mode below 2: pi/2");
    check(d.count_modes_below(2.2, 100) == 3, "three Laplace modes below 2.2: a periodic pair");
    check(d.count_modes_below(3.2, 100) == 6, "six Laplace modes below 3.2");
    check(d.count_modes_below(1e3, 5) == 5, "Laplace modes counted up to the cap");
    check_close(p.fluid.gravity, Tensor<1, 3>({0, 0, -9.81}), "gravity (0, 0, -9.81)");
    check_close(p.fluid.viscosity, 0.03, "viscosity 3e-2");
    check_close(p.fluid.hydrostatic_gradient(), Tensor<1, 3>({1, 0, -19.62}),
                "rho g + f = (1, 0, -19.62)");
    const ParticleSet<3> &ps = p.particles;
    check(ps.size() == 2, "2 particles");
    if (ps.size() == 2)
      {
        check_close(Tensor<1, 3>(ps[0].position), Tensor<1, 3>({0.5, 1, 1.5}), "particle 1 centre");
        check_close(Tensor<1, 3>(ps[1].position), Tensor<1, 3>({0.5, 0.5, 0.5}),
                    "particle 2 centre");
        check_close(ps[1].bounding_radius(), 0.1, "particle 2 radius");
        check(ps[1].motion == ParticleMotion::free, "particle 2 'free'");
        check(ps[0].first_unknown == 0 && ps[1].first_unknown == 6, "unknown offsets 0 and 6");
      }
    check(ps.n_unknowns() == 12, "particle block: 12 unknowns (two free 3D particles)");
    check(ps.closure() == AngularVelocityClosure::kinematic, "closure kinematic");

    // No particles at all: plain flow.
    Parsed<3> empty;
    Parsed<3> moving;
    parse<3>(base_3d + override_entry("Particles/Particles",
                                      "0.5, 1, 1.5 : 0.2 : 2 : prescribed : 0, -0.5, 0 : 1, 2, 3 ;"
                                      "0.5, 1, 2.5 : 0.2 : 2 : prescribed : 1, 0, 0"),
             moving);
    {
      const auto &m = moving.particles;
      check(m[0].motion == ParticleMotion::prescribed && m[1].motion == ParticleMotion::prescribed,
            "'prescribed' parsed");
      check(m.n_unknowns() == 0 && m[0].first_unknown == numbers::invalid_unsigned_int,
            "prescribed particles have no particle unknowns");
      check_close(m[0].velocity, Tensor<1, 3>({0, -0.5, 0}), "prescribed V");
      check_close(m[0].velocity_old2, Tensor<1, 3>({0, -0.5, 0}), "prescribed V fills the history");
      check_close(m[0].omega, Tensor<1, 3>({1, 2, 3}), "prescribed omega");
      check_close(m[1].omega, Tensor<1, 3>(), "omega defaults to 0");
    }
    parse<3>(base_3d + override_entry("Particles/Particles", ""), empty);
    check(empty.particles.size() == 0 && empty.particles.n_unknowns() == 0, "empty particle list");
    // Touching the wall of a periodic direction is fine as long as it does not cross.
    Parsed<3> near;
    parse<3>(base_3d + override_entry("Particles/Particles", "0.11, 1, 2.89 : 0.1 : 1"), near);
    check(near.particles.size() == 1, "particle 0.01 from periodic boundaries accepted");
  }

  void test_bad_input()
  {
    std::cout << "Bad input" << std::endl;
    // Vector lengths and numbers.
    check_rejected<3>("Geometry/Lower corner", "0, 0", "needs 3");
    check_rejected<3>("Gravity", "0, -9.81", "'Gravity' needs 3");
    check_rejected<2>("Geometry/Upper corner", "1, 4, 1", "needs 2");
    check_rejected<2>("Fluid/Body force", "0, 0, 0", "'Fluid/Body force' needs 2");
    check_rejected<2>("Geometry/Lower corner", "-1, abc", "not a finite number");
    check_rejected<2>("Geometry/Lower corner", "-1, ", "not a finite number");
    check_rejected<2>("Geometry/Lower corner", "-1, inf", "not a finite number");
    check_rejected<2>("Fluid/Viscosity", "1e-2x", "not a finite number");
    // Box.
    check_rejected<2>("Geometry/Lower corner", "2, 0", "lower corner");
    check_rejected<2>("Geometry/Lower corner", "1, 0", "lower corner"); // equal in x
    check_rejected<3>("Geometry/Upper corner", "1, 2, -1", "lower corner");
    check_rejected<2>("Geometry/Subdivisions", "0, 8", "Subdivisions");
    check_rejected<3>("Geometry/Subdivisions", "2, 2.5, 6", "Subdivisions");
    check_rejected<3>("Geometry/Subdivisions", "2, -1, 6", "Subdivisions");
    check_rejected<2>("Geometry/Periodic directions", "z", "is not a direction");
    check_rejected<3>("Geometry/Periodic directions", "x, w", "is not a direction");
    // Walls.
    check_rejected<3>("Boundary conditions/Wall velocities", "w+: 1,0,0", "'w+' is not a face");
    check_rejected<2>("Boundary conditions/Wall velocities", "z+: 1, 0", "'z+' is not a face");
    check_rejected<3>("Boundary conditions/Wall velocities", "y+: 0,1,0", "tangentially");
    check_rejected<2>("Boundary conditions/Wall velocities", "x-: 1, 0", "tangentially");
    check_rejected<3>("Boundary conditions/Wall velocities", "x-: 0,1,0", "periodic direction");
    check_rejected<3>("Boundary conditions/Wall velocities", "y+ 1,0,0", "is not of the form");
    check_rejected<3>("Boundary conditions/Wall velocities", "y+: 1,0", "needs 3");
    // Fluid.
    check_rejected<2>("Fluid/Viscosity", "0", "Viscosity");
    check_rejected<2>("Fluid/Viscosity", "-1", "'Fluid/Viscosity' must be positive");
    check_rejected<2>("Fluid/Density", "0", "'Fluid/Density' must be positive");
    check_rejected<3>("Fluid/Density", "-2", "'Fluid/Density' must be positive");
    // Particles.
    const std::string P = "Particles/Particles";
    check_rejected<2>(P, "5, 1 : 0.25 : 1", "outside the box");
    check_rejected<2>(P, "0, -0.5 : 0.25 : 1", "outside the box");
    check_rejected<3>(P, "0.5, 1, 3.01 : 0.2 : 1", "outside the box"); // past a periodic face
    check_rejected<2>(P, "0.9, 1 : 0.25 : 1", "overlaps a wall");
    check_rejected<2>(P, "0, 3.75 : 0.25 : 1", "overlaps a wall"); // touching counts
    check_rejected<3>(P, "0.5, 0.15, 1.5 : 0.2 : 1", "overlaps a wall");
    check_rejected<3>(P, "0.5, 1, 1.5 : 0.5 : 1", "would overlap its own periodic image");
    check_rejected<2>(P, "0, 1 : 0.3 : 1 ; 0.4, 1.2 : 0.3 : 1", "Particles 0 and 1 overlap");
    check_rejected<3>(P, "0.5,1,1.5:0.2:2; 0.5,0.5,0.5:0.1:3; 0.5,1.3,1.5:0.15:1",
                      "Particles 0 and 2 overlap");
    check_rejected<2>(P, "0, 1 : 0 : 1", "radius must be positive");
    check_rejected<2>(P, "0, 1 : -0.2 : 1", "radius must be positive");
    check_rejected<2>(P, "0, 1 : 0.2 : 0", "density must be positive");
    check_rejected<3>(P, "0.5, 1, 1.5 : 0.2 : -1", "density must be positive");
    check_rejected<3>(P, "0,1,0:0.2:1.5;;0,0,0:0.1:1", "(entry 2)' is empty");
    check_rejected<2>(P, "0, 1 : 0.2 : 1 ;", "(entry 2)' is empty");
    check_rejected<2>(P, "0, 1 : 0.2", "is not of the form");
    check_rejected<2>(P, "0, 1 : 0.2 : 1 : stuck", "is not 'free', 'fixed' or 'prescribed'");
    check_rejected<2>(P, "0, 1 : 0.2 : 1 : prescribed", "'prescribed' needs a velocity");
    check_rejected<2>(P, "0, 1 : 0.2 : 1 : fixed : 1, 0", "only 'prescribed' takes a velocity");
    check_rejected<2>(P, "0, 1 : 0.2 : 1 : prescribed : 1, 0, 0", "velocity' needs 2");
    check_rejected<2>(P, "0, 1 : 0.2 : 1 : prescribed : 1, 0 : 0, 1",
                      "in 2D an angular velocity is w_z alone");
    check_rejected<3>(P, "0.5, 1, 1.5 : 0.2 : 1 : prescribed : 0, 0, 1 : 2", "velocity' needs 3");
    check_rejected<2>(P, "0, 1 : 0.2 : 1 : prescribed : 1, 0 : 1 : 2", "is not of the form");
    check_rejected<2>(P, "0, 1, 1 : 0.2 : 1", "needs 2");
    check_rejected<2>(P, "0, 1 : r : 1", "not a finite number");

    // ParameterHandler itself rejects an undeclared entry or a value outside the pattern
    // while parsing, before any parse_parameters runs.
    const std::vector<std::pair<std::string, std::string>> pattern_cases = {
      {"Foo", "1"}, {"Geometry/Global refinements", "13"}, {"Fluid/Convection", "maybe"}};
    for (const auto &[path, value] : pattern_cases)
      {
        const std::string input = override_entry(path, value);
        const std::string phrase = path.substr(path.find('/') + 1);
        ParameterHandler prm;
        declare_all_parameters(prm);
        std::string message;
        try
          {
            prm.parse_input_from_string(base_2d + input);
          }
        catch (const std::exception &exc)
          {
            message = ParameterTools::one_line_message(exc);
          }
        check(!message.empty() && message.find(phrase) != std::string::npos,
              path + " = " + value + " throws from parse_input_from_string naming " + phrase,
              message.empty() ? "no exception" : "message: " + message);
        std::cout << "          (" << message << ")" << std::endl;
      }
  }

  /// A misspelled name is refused before ParameterHandler reads the file, with its line,
  /// its subsection and the declared name closest to it.
  void test_misspelled_names()
  {
    ParameterHandler prm;
    declare_all_parameters(prm);
    const auto message = [&](const std::string &text) -> std::string {
      try
        {
          ParameterTools::check_names(prm, text, "scene.prm");
        }
      catch (const std::exception &exc)
        {
          return ParameterTools::one_line_message(exc);
        }
      return "";
    };
    check(message("set Dimension = 2\nsubsection Geometry\n  set Lower  corner = 0, 0\nend\n")
            .empty(),
          "declared names pass (blanks inside a name count as one)");
    const std::string entry =
      message("set Dimension = 2\nsubsection Geometry\n  set Lower corenr = 0, 0\nend\n");
    check(entry.find("Line 3 of 'scene.prm'") != std::string::npos &&
            entry.find("no entry 'Lower corenr' in subsection 'Geometry'") != std::string::npos &&
            entry.find("Did you mean 'Lower corner'?") != std::string::npos,
          "a misspelled entry: its line, its subsection and the closest name", entry);
    const std::string section = message("subsection Geomtry\n  set Lower corner = 0, 0\nend\n");
    check(section.find("Line 1 of 'scene.prm'") != std::string::npos &&
            section.find("no subsection 'Geomtry' at the top level") != std::string::npos &&
            section.find("Did you mean 'Geometry'?") != std::string::npos,
          "a misspelled subsection: its line and the closest name", section);
    const std::string nested =
      message("subsection Particles\n  subsection Random particles\n    set Cuont = 3\n  end\nend\n");
    check(nested.find("in subsection 'Particles/Random particles'") != std::string::npos &&
            nested.find("Did you mean 'Count'?") != std::string::npos,
          "a nested subsection is named by its path", nested);
    check(message("set Completely different name = 1\n").find("Did you mean") == std::string::npos,
          "no suggestion when nothing is close");
  }
} // namespace

int main()
{
  try
    {
      test_good_2d();
      test_good_3d();
      test_bad_input();
      test_misspelled_names();
    }
  catch (const std::exception &exc)
    {
      std::cerr << "Unexpected exception: " << ParameterTools::one_line_message(exc) << std::endl;
      return 2;
    }
  return unit_check::summary();
}
