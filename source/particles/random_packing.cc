#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/cell_list.h>
#include <fdparticle/particles/contact_geometry.h>
#include <fdparticle/particles/ellipsoid.h>
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
                        "Number of free particles placed at random, without overlap, after "
                        "those of Particles and Particle file (which they avoid).");
      prm.declare_entry("Shape", "ball", Patterns::Anything(),
                        "ball, or 'ellipse a, b' (2D) or 'ellipsoid a, b, c' (3D): the ratios "
                        "of the semi-axes, scaled so that the largest is the Radius drawn; "
                        "each ellipse or ellipsoid is turned at random, all orientations "
                        "equally likely.");
      prm.declare_entry("Radius", "0.1", Patterns::Anything(),
                        "Radius of each ball (largest semi-axis of each ellipse or ellipsoid), "
                        "or 'min, max': uniform in [min, max].");
      prm.declare_entry("Density", "2", Patterns::Double(0), "Density of each particle.");
      prm.declare_entry("Lower corner", "", Patterns::Anything(),
                        "Lower corner of the sub-box the balls lie in; empty: the box. "
                        "Where the sub-box spans a periodic direction the centres may lie "
                        "anywhere in it and the balls cross its faces.");
      prm.declare_entry("Upper corner", "", Patterns::Anything(),
                        "Upper corner of the sub-box; empty: the box.");
      prm.declare_entry("Minimum gap", "0", Patterns::Double(0),
                        "Smallest gap left between two particles and between a particle and a "
                        "wall.");
      prm.declare_entry("Seed", "1", Patterns::Integer(0),
                        "Seed of the random numbers: the same seed gives the same particles.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void RandomPacking<dim>::parse_parameters(ParameterHandler &prm, const Box<dim> &box)
  {
    using namespace ParameterTools;
    domain = box;
    prm.enter_subsection("Random particles");
    n_particles = prm.get_integer("Count");
    axis_ratios = Tensor<1, dim>();
    if (const std::string shape = trim(prm.get("Shape")); shape != "ball")
      {
        const std::string name = "Particles/Random particles/Shape";
        const std::string form = std::string("'ball' or ") +
                                 (dim == 2 ? "'ellipse a, b'" : "'ellipsoid a, b, c'") +
                                 " (the ratios of the semi-axes)";
        Particle<dim> probe;
        read_shape(shape, name, probe);
        AssertThrow(!probe.shape->is_isotropic(),
                    ExcMessage("Parameter '" + name + "' is " + form + ", got '" + shape + "'."));
        AssertThrow(probe.orientation.isApprox(Eigen::Quaterniond::Identity(), 0.0),
                    ExcMessage("Parameter '" + name + "' takes no angle: the random particles "
                               "are turned at random. It is " + form + "."));
        const Tensor<2, dim> S = probe.shape->semi_axes_tensor();
        double largest = 0;
        for (unsigned int d = 0; d < dim; ++d)
          largest = std::max(largest, S[d][d]);
        for (unsigned int d = 0; d < dim; ++d)
          axis_ratios[d] = S[d][d] / largest;
      }
    const std::vector<std::string> radii = split(prm.get("Radius"), ',');
    AssertThrow(radii.size() == 1 || radii.size() == 2,
                ExcMessage("Parameter 'Particles/Random particles/Radius' is one radius or "
                           "'min, max', got '" + prm.get("Radius") + "'."));
    min_radius = to_double(radii.front(), "Particles/Random particles/Radius");
    max_radius = to_double(radii.back(), "Particles/Random particles/Radius");
    AssertThrow(min_radius > 0 && max_radius >= min_radius,
                ExcMessage("Parameter 'Particles/Random particles/Radius' needs 0 < min <= "
                           "max, got '" + prm.get("Radius") + "'."));
    density = prm.get_double("Density");
    AssertThrow(density > 0 || n_particles == 0,
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
  std::vector<Particle<dim>>
  RandomPacking<dim>::place(const std::vector<Particle<dim>> &existing) const
  {
    std::vector<Particle<dim>> placed;
    if (n_particles == 0)
      return placed;
    std::mt19937_64 engine(seed);
    // A double in (0, 1) from the top 53 bits, the same on every platform.
    const auto uniform = [&engine]() {
      return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53;
    };
    // An orientation uniform over all rotations: an angle in 2D, in 3D a unit quaternion
    // uniform on the sphere S³ (Shoemake 1992).
    const auto orientation = [&uniform]() {
      if (dim == 2)
        return Eigen::Quaterniond(
          Eigen::AngleAxisd(2 * numbers::PI * uniform(), Eigen::Vector3d::UnitZ()));
      const double u = uniform(), a = 2 * numbers::PI * uniform(), b = 2 * numbers::PI * uniform();
      return Eigen::Quaterniond(std::sqrt(1 - u) * std::sin(a), std::sqrt(1 - u) * std::cos(a),
                                std::sqrt(u) * std::sin(b), std::sqrt(u) * std::cos(b));
    };
    const bool balls = axis_ratios.norm() == 0;

    double largest = max_radius;
    for (const Particle<dim> &p : existing)
      largest = std::max(largest, p.bounding_radius());
    CellList<dim>              list(domain, 2 * largest + min_gap);
    std::vector<Particle<dim>> all = existing;
    for (unsigned int k = 0; k < all.size(); ++k)
      list.insert(k, all[k].position);

    double placed_volume = 0;
    for (unsigned int n = 0; n < n_particles; ++n)
      {
        const double  r = min_radius + (max_radius - min_radius) * uniform();
        Particle<dim> p;
        p.density = density;
        if (balls)
          p.shape = std::make_shared<const Sphere<dim>>(r);
        else
          {
            p.shape = std::make_shared<const Ellipsoid<dim>>(r * axis_ratios,
                                                             "Particles/Random particles/Shape");
            p.orientation = p.orientation_old = orientation();
          }
        p.place(Point<dim>(), p.orientation);
        // The centres that keep the particle in the sub-box and off the walls by the gap.
        // A sub-box that spans a periodic direction has no faces there: the particle may
        // cross it (its images), so every centre is allowed and the suspension is uniform.
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
            Tensor<1, dim> e;
            e[d] = 1;
            const double wall_gap = domain.is_periodic(d) ? 0.0 : min_gap;
            from[d] = std::max(lower[d], domain.lower_corner()[d] + wall_gap) + p.extent(-e);
            to[d] = std::min(upper[d], domain.upper_corner()[d] - wall_gap) - p.extent(e);
            AssertThrow(from[d] < to[d],
                        ExcMessage("Particles/Random particles: a particle of radius " +
                                   ParameterTools::format_short(r) +
                                   " does not fit in the sub-box with the minimum gap."));
          }
        bool done = false;
        for (unsigned int draw = 0; draw < max_draws_per_particle && !done; ++draw)
          {
            Point<dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = from[d] + (to[d] - from[d]) * uniform();
            p.place(x, p.orientation);
            bool free = true;
            list.for_each_near(x, [&](const unsigned int k) {
              if (!free)
                return;
              const Tensor<1, dim> offset = list.offset(x, all[k].position);
              if (offset.norm() >= r + all[k].bounding_radius() + min_gap)
                return;
              // The bounding balls come closer than the gap: so do two balls, and other
              // shapes where their true gap does.
              free = !(balls && all[k].shape->is_isotropic()) &&
                     ContactGeometry<dim>::pair(p, all[k], offset).gap >= min_gap;
            });
            if (free)
              {
                p.position = p.position_old = x;
                list.insert(all.size(), x);
                all.push_back(p);
                placed.push_back(p);
                placed_volume += p.volume();
                done = true;
              }
          }
        double sub_box_volume = 1;
        for (unsigned int d = 0; d < dim; ++d)
          sub_box_volume *= upper[d] - lower[d];
        AssertThrow(done,
                    ExcMessage("Particles/Random particles: placed " + std::to_string(n) +
                               " of " + std::to_string(n_particles) + " particles (solid "
                               "fraction " +
                               ParameterTools::format_short(placed_volume / sub_box_volume) +
                               " of the sub-box) and found no place for the next in " +
                               std::to_string(max_draws_per_particle) +
                               " draws. Random placement of balls jams near a solid fraction "
                               "of " + (dim == 2 ? "0.55" : "0.38") +
                               ": ask for fewer or smaller particles, a smaller minimum gap or "
                               "a larger sub-box."));
      }
    return placed;
  }

  template class RandomPacking<2>;
  template class RandomPacking<3>;
} // namespace fdparticle
