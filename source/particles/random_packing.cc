#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/cell_list.h>
#include <fdparticle/particles/random_packing.h>
#include <fdparticle/particles/sphere.h>

#include <algorithm>
#include <random>

namespace fdparticle
{
  template <int dim>
  void RandomPacking<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Random particles");
    {
      prm.declare_entry("Count", "0", Patterns::Integer(0),
                        "Number of free balls placed at random, without overlap, after the "
                        "balls of Particles and Particle file (which they avoid).");
      prm.declare_entry("Radius", "0.1", Patterns::Anything(),
                        "Radius of each ball, or 'min, max': radii uniform in [min, max].");
      prm.declare_entry("Density", "2", Patterns::Double(0), "Density of each ball.");
      prm.declare_entry("Lower corner", "", Patterns::Anything(),
                        "Lower corner of the sub-box the balls lie in; empty: the box. "
                        "Where the sub-box spans a periodic direction the centres may lie "
                        "anywhere in it and the balls cross its faces.");
      prm.declare_entry("Upper corner", "", Patterns::Anything(),
                        "Upper corner of the sub-box; empty: the box.");
      prm.declare_entry("Minimum gap", "0", Patterns::Double(0),
                        "Smallest gap left between two balls and between a ball and a wall.");
      prm.declare_entry("Seed", "1", Patterns::Integer(0),
                        "Seed of the random numbers: the same seed gives the same balls.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void RandomPacking<dim>::parse_parameters(ParameterHandler &prm, const Box<dim> &box)
  {
    using namespace ParameterTools;
    domain = box;
    prm.enter_subsection("Random particles");
    n_balls = prm.get_integer("Count");
    const std::vector<std::string> radii = split(prm.get("Radius"), ',');
    AssertThrow(radii.size() == 1 || radii.size() == 2,
                ExcMessage("Parameter 'Particles/Random particles/Radius' is one radius or "
                           "'min, max', got '" + prm.get("Radius") + "'."));
    min_radius = to_double(radii.front(), "Particles/Random particles/Radius");
    max_radius = to_double(radii.back(), "Particles/Random particles/Radius");
    AssertThrow(min_radius > 0 && max_radius >= min_radius,
                ExcMessage("Parameter 'Particles/Random particles/Radius' needs 0 < min <= "
                           "max, got '" + prm.get("Radius") + "'."));
    ball_density = prm.get_double("Density");
    AssertThrow(ball_density > 0 || n_balls == 0,
                ExcMessage("Parameter 'Particles/Random particles/Density' must be positive."));
    min_gap = prm.get_double("Minimum gap");
    seed = prm.get_integer("Seed");
    lower = box.lower_corner();
    upper = box.upper_corner();
    if (!trim(prm.get("Lower corner")).empty())
      lower = Point<dim>(get_tensor<dim>(prm, "Lower corner",
                                         "Particles/Random particles/Lower corner"));
    if (!trim(prm.get("Upper corner")).empty())
      upper = Point<dim>(get_tensor<dim>(prm, "Upper corner",
                                         "Particles/Random particles/Upper corner"));
    prm.leave_subsection();
    for (unsigned int d = 0; d < dim; ++d)
      AssertThrow(box.lower_corner()[d] <= lower[d] && lower[d] < upper[d] &&
                    upper[d] <= box.upper_corner()[d],
                  ExcMessage("The sub-box of Particles/Random particles must lie in the box "
                             "(Geometry/Lower corner, Upper corner) and have a positive size "
                             "in every direction."));
  }

  template <int dim>
  std::vector<typename RandomPacking<dim>::Ball>
  RandomPacking<dim>::place(const std::vector<Ball> &existing) const
  {
    std::vector<Ball> balls;
    if (n_balls == 0)
      return balls;
    std::mt19937_64 engine(seed);
    // A double in (0, 1) from the top 53 bits, the same on every platform.
    const auto uniform = [&engine]() {
      return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53;
    };

    double largest = max_radius;
    for (const Ball &b : existing)
      largest = std::max(largest, b.radius);
    CellList<dim>     list(domain, 2 * largest + min_gap);
    std::vector<Ball> all = existing;
    for (unsigned int k = 0; k < all.size(); ++k)
      list.insert(k, all[k].center);

    double placed_volume = 0;
    for (unsigned int n = 0; n < n_balls; ++n)
      {
        const double r = min_radius + (max_radius - min_radius) * uniform();
        // The centres that keep the ball in the sub-box and off the walls by the gap. A
        // sub-box that spans a periodic direction has no faces there: the ball may cross
        // it (its images), so every centre is allowed and the suspension is uniform.
        Point<dim> from, to;
        for (unsigned int d = 0; d < dim; ++d)
          {
            if (domain.is_periodic(d) && lower[d] == domain.lower_corner()[d] &&
                upper[d] == domain.upper_corner()[d])
              {
                from[d] = lower[d];
                to[d] = upper[d];
                continue;
              }
            const double wall_gap = domain.is_periodic(d) ? 0.0 : min_gap;
            from[d] = std::max(lower[d], domain.lower_corner()[d] + wall_gap) + r;
            to[d] = std::min(upper[d], domain.upper_corner()[d] - wall_gap) - r;
            AssertThrow(from[d] < to[d],
                        ExcMessage("Particles/Random particles: a ball of radius " +
                                   ParameterTools::format_short(r) +
                                   " does not fit in the sub-box with the minimum gap."));
          }
        bool placed = false;
        for (unsigned int draw = 0; draw < max_draws_per_ball && !placed; ++draw)
          {
            Point<dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = from[d] + (to[d] - from[d]) * uniform();
            bool free = true;
            list.for_each_near(x, [&](const unsigned int k) {
              free = free && list.offset(x, all[k].center).norm() >= r + all[k].radius + min_gap;
            });
            if (free)
              {
                list.insert(all.size(), x);
                all.push_back(Ball{x, r});
                balls.push_back(Ball{x, r});
                placed_volume += Sphere<dim>(r).volume();
                placed = true;
              }
          }
        double sub_box_volume = 1;
        for (unsigned int d = 0; d < dim; ++d)
          sub_box_volume *= upper[d] - lower[d];
        AssertThrow(placed,
                    ExcMessage("Particles/Random particles: placed " + std::to_string(n) +
                               " of " + std::to_string(n_balls) + " balls (solid fraction " +
                               ParameterTools::format_short(placed_volume / sub_box_volume) +
                               " of the sub-box) and found no place for the next in " +
                               std::to_string(max_draws_per_ball) +
                               " draws. Random placement jams near a solid fraction of " +
                               (dim == 2 ? "0.55" : "0.38") +
                               ": ask for fewer or smaller balls, a smaller minimum gap or a "
                               "larger sub-box."));
      }
    return balls;
  }

  template class RandomPacking<2>;
  template class RandomPacking<3>;
} // namespace fdparticle
