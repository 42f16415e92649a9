// Unit test of fdparticle::PairSearch and fdparticle::Collisions, in 2D and 3D
// (include/fdparticle/particles/pair_search.h, collisions.h).
//
// PairSearch is compared with the comparison of all pairs, done here with the nearest
// periodic image found by trying every shift by a box length. The collision force of the
// particle rows is checked for being equal and opposite on a pair and zero out of range, and
// its derivative in the particle block D against central differences of the residual in
// the particle velocities. The program prints each check and returns 1 if any fails.

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/core/fluid.h>
#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/particles/collisions.h>
#include <fdparticle/particles/pair_search.h>
#include <fdparticle/particles/particle_set.h>

#include "unit_check.h"

#include <algorithm>
#include <random>
#include <set>
#include <string>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  /// Step of the central differences in the velocities, and the agreement asked of them
  /// relative to the largest entry of D: the force is smooth inside the range, so only the
  /// O(step²) truncation and round-off limit it.
  constexpr double fd_step      = 1e-7;
  constexpr double fd_tolerance = 1e-6;

  template <int dim>
  void parse(ParameterHandler &prm, const std::string &periodic, const std::string &particles,
             Domain<dim> &domain, Fluid<dim> &fluid, ParticleSet<dim> &set,
             Collisions<dim> &collisions)
  {
    declare_all_parameters(prm);
    prm.parse_input_from_string(
      "set Dimension = " + std::to_string(dim) + "\nset Gravity = " +
      (dim == 2 ? "0, -9.8" : "0, -9.8, 0") + "\nsubsection Geometry\n  set Lower corner = " +
      (dim == 2 ? "0, 0" : "0, 0, 0") + "\n  set Upper corner = " +
      (dim == 2 ? "1, 1.5" : "1, 1.5, 1.2") + "\n  set Subdivisions = " +
      (dim == 2 ? "4, 6" : "4, 6, 5") + "\n  set Periodic directions = " + periodic +
      "\nend\nsubsection Particles\n  set Particles = " + particles +
      "\nend\nsubsection Collisions\n  set Model = repulsion\n  set Range = 0.05\nend\n");
    domain.parse_parameters(prm);
    fluid.parse_parameters(prm);
    set.parse_parameters(prm, domain);
    collisions.parse_parameters(prm);
    collisions.initialize(domain, fluid, set, 0.01);
  }

  template <int dim>
  void test_pair_search(const std::string &periodic)
  {
    std::cout << dim << "D pair search, periodic directions '" << periodic << "'" << std::endl;
    ParameterHandler prm;
    Domain<dim>      domain;
    Fluid<dim>       fluid;
    ParticleSet<dim> set;
    Collisions<dim>  collisions;
    parse(prm, periodic, dim == 2 ? "0.5, 0.5 : 0.1 : 2" : "0.5, 0.5, 0.5 : 0.1 : 2", domain,
          fluid, set, collisions);
    const Point<dim> lower = domain.lower_corner(), upper = domain.upper_corner();

    // Random balls (overlaps allowed: the search does not care), radii 0.01 … 0.06.
    std::mt19937                           random(77 + dim);
    std::uniform_real_distribution<double> uniform(0, 1);
    std::vector<Point<dim>>                x(300);
    std::vector<double>                    r(x.size());
    for (unsigned int k = 0; k < x.size(); ++k)
      {
        for (unsigned int d = 0; d < dim; ++d)
          x[k][d] = lower[d] + uniform(random) * (upper[d] - lower[d]);
        r[k] = 0.01 + 0.05 * uniform(random);
      }
    for (const double reach : {0.0, 0.02, 0.3})
      {
        std::set<std::pair<unsigned int, unsigned int>> expected;
        double largest_error = 0;
        for (unsigned int i = 0; i < x.size(); ++i)
          for (unsigned int j = i + 1; j < x.size(); ++j)
            {
              // Nearest image by trying all shifts by −1, 0, +1 box lengths.
              double best = std::numeric_limits<double>::max();
              for (unsigned int s = 0; s < std::pow(3, dim); ++s)
                {
                  Tensor<1, dim> offset = x[i] - x[j];
                  unsigned int   code   = s;
                  bool           allowed = true;
                  for (unsigned int d = 0; d < dim; ++d, code /= 3)
                    {
                      const int shift = int(code % 3) - 1;
                      if (shift != 0 && !domain.is_periodic(d))
                        allowed = false;
                      offset[d] += shift * (upper[d] - lower[d]);
                    }
                  if (allowed)
                    best = std::min(best, offset.norm());
                }
              if (best - r[i] - r[j] < reach)
                expected.insert({i, j});
            }
        std::set<std::pair<unsigned int, unsigned int>> found;
        for (const auto &p : PairSearch<dim>(domain).pairs(x, r, reach))
          {
            found.insert({p.i, p.j});
            largest_error = std::max(largest_error, std::abs(p.offset.norm() - r[p.i] - r[p.j] - p.gap));
          }
        check(found == expected, "reach " + std::to_string(reach) + ": the " +
                                   std::to_string(expected.size()) + " pairs of the comparison of all pairs",
              std::to_string(found.size()) + " found");
        check(largest_error < 1e-14, "gaps are |offset| - r_i - r_j");
      }
  }

  template <int dim>
  void test_force(const std::string &periodic, const std::string &particles, const bool in_range)
  {
    std::cout << dim << "D collision force, periodic '" << periodic << "', particles " << particles
              << std::endl;
    ParameterHandler prm;
    Domain<dim>      domain;
    Fluid<dim>       fluid;
    ParticleSet<dim> set;
    Collisions<dim>  collisions;
    parse(prm, periodic, particles, domain, fluid, set, collisions);
    // A BDF2 step of 0.01 with a history, and velocities that turn the pair a little.
    const std::array<double, 3> c{{1.5 / 0.01, -2 / 0.01, 0.5 / 0.01}};
    std::mt19937                           random(5 + dim);
    std::uniform_real_distribution<double> uniform(-0.1, 0.1);
    for (unsigned int k = 0; k < set.size(); ++k)
      {
        set[k].position_old = set[k].position;
        for (unsigned int d = 0; d < dim; ++d)
          set[k].velocity[d] = uniform(random);
      }
    const unsigned int m  = set.n_unknowns();
    const auto residual = [&](const Eigen::VectorXd &y, Eigen::MatrixXd *D) {
      set.set_unknowns(y);
      for (unsigned int k = 0; k < set.size(); ++k)
        set[k].contact_force = Tensor<1, dim>();
      Eigen::VectorXd r = Eigen::VectorXd::Zero(m);
      collisions.add_to_particle_rows(set, c, r, D);
      return r;
    };
    const Eigen::VectorXd y0 = set.get_unknowns();
    Eigen::MatrixXd       D  = Eigen::MatrixXd::Zero(m, m);
    const Eigen::VectorXd r0 = residual(y0, &D);
    const Tensor<1, dim>  F0 = set[0].contact_force;
    if (!in_range)
      {
        check(r0.norm() == 0 && D.norm() == 0 && F0.norm() == 0,
              "no force and no derivative out of range");
        return;
      }
    check(F0.norm() > 0, "a force in range");
    check((F0 + set[1].contact_force).norm() <= 1e-14 * F0.norm(), "equal and opposite");
    Eigen::MatrixXd difference(m, m);
    for (unsigned int j = 0; j < m; ++j)
      {
        Eigen::VectorXd yp = y0, ym = y0;
        yp[j] += fd_step;
        ym[j] -= fd_step;
        difference.col(j) = (residual(yp, nullptr) - residual(ym, nullptr)) / (2 * fd_step);
      }
    check((difference - D).cwiseAbs().maxCoeff() <= fd_tolerance * D.cwiseAbs().maxCoeff(),
          "D is the derivative of the residual in the velocities (central differences)",
          "largest difference " + std::to_string((difference - D).cwiseAbs().maxCoeff()) +
            " of " + std::to_string(D.cwiseAbs().maxCoeff()));
  }
} // namespace

int main()
{
  try
    {
      test_pair_search<2>("");
      test_pair_search<2>("x, y");
      test_pair_search<3>("x, z");
      // A pair 0.03 apart (range 0.05), off the line of the axes; the same across the
      // periodic boundary in x; a pair 0.1 apart (out of range).
      test_force<2>("", "0.4, 0.5 : 0.1 : 2 ; 0.6, 0.62 : 0.12 : 3", true);
      test_force<2>("x", "0.11, 0.5 : 0.1 : 2 ; 0.88, 0.55 : 0.1 : 3", true);
      test_force<2>("", "0.3, 0.5 : 0.1 : 2 ; 0.6, 0.5 : 0.1 : 3", false);
      test_force<3>("", "0.4, 0.5, 0.5 : 0.1 : 2 ; 0.6, 0.62, 0.55 : 0.12 : 3", true);
      test_force<3>("y", "0.5, 0.11, 0.5 : 0.1 : 2 ; 0.52, 1.38, 0.51 : 0.1 : 3", true);
    }
  catch (const std::exception &exc)
    {
      std::cerr << "Unexpected exception: " << exc.what() << std::endl;
      return 2;
    }
  return unit_check::summary();
}
