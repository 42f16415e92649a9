#include <deal.II/base/numbers.h>

#include <fdparticle/base/box.h>
#include <fdparticle/base/parameter_tools.h>

#include <algorithm>
#include <functional>

namespace fdparticle
{
  template <int dim>
  void Box<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    {
      prm.declare_entry("Lower corner", "-0.5, -0.5, -0.5", Patterns::Anything(),
                        "Lower corner of the box, Dimension comma-separated numbers.");
      prm.declare_entry("Upper corner", "0.5, 1.5, 0.5", Patterns::Anything(),
                        "Upper corner of the box; every coordinate above the lower corner's.");
      prm.declare_entry("Periodic directions", "", Patterns::Anything(),
                        "Comma-separated subset of x, y, z; the other directions are "
                        "bounded by no-slip walls.");
    }
    prm.leave_subsection();
    prm.enter_subsection("Boundary conditions");
    {
      prm.declare_entry("Wall velocities", "", Patterns::Anything(),
                        "';'-separated 'face: vector' entries, faces x- x+ y- y+ z- z+, "
                        "e.g. 'y+: 1, 0, 0'; tangential velocities only. Unlisted walls are at "
                        "rest (no-slip).");
    }
    prm.leave_subsection();
  }

  template <int dim>
  std::string Box<dim>::face_name(const types::boundary_id face)
  {
    return std::string(1, "xyz"[face / 2]) + (face % 2 == 0 ? "-" : "+");
  }

  template <int dim>
  void Box<dim>::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    prm.enter_subsection("Geometry");
    {
      lower = Point<dim>(get_tensor<dim>(prm, "Lower corner", "Geometry/Lower corner"));
      upper = Point<dim>(get_tensor<dim>(prm, "Upper corner", "Geometry/Upper corner"));
      for (unsigned int d = 0; d < dim; ++d)
        AssertThrow(lower[d] < upper[d],
                    ExcMessage("Geometry: the lower corner must lie below the upper corner in "
                               "every direction (direction " +
                               std::string(1, "xyz"[d]) + ": " + std::to_string(lower[d]) +
                               " >= " + std::to_string(upper[d]) + ")."));
      for (unsigned int d = 0; d < dim; ++d)
        AssertThrow(std::abs(lower[d]) <= max_length && std::abs(upper[d]) <= max_length &&
                      upper[d] - lower[d] >= 1 / max_length,
                    ExcMessage("Geometry: the box must lie within +-" + format_short(max_length) +
                               " and be at least " + format_short(1 / max_length) +
                               " wide in every direction (direction " +
                               std::string(1, "xyz"[d]) + ": from " + format_short(lower[d]) +
                               " to " + format_short(upper[d]) +
                               "); choose units in which the scene's lengths are moderate "
                               "numbers."));
      periodic.fill(false);
      for (const std::string &name : split(prm.get("Periodic directions"), ','))
        {
          if (name.empty())
            continue;
          const auto d = std::string("xyz").find(name);
          AssertThrow(name.size() == 1 && d != std::string::npos && d < dim,
                      ExcMessage("Parameter 'Geometry/Periodic directions': '" + name +
                                 "' is not a direction of this " + std::to_string(dim) +
                                 "D box (use x, y" + (dim == 3 ? ", z" : "") + ")."));
          periodic[d] = true;
        }
    }
    prm.leave_subsection();

    prm.enter_subsection("Boundary conditions");
    {
      for (auto &v : wall_velocities)
        v = Tensor<1, dim>();
      for (const std::string &entry : split(prm.get("Wall velocities"), ';'))
        {
          if (entry.empty())
            continue;
          const auto colon = entry.find(':');
          AssertThrow(colon != std::string::npos,
                      ExcMessage("Parameter 'Boundary conditions/Wall velocities': entry '" +
                                 entry + "' is not of the form 'face: vx, vy[, vz]'."));
          const std::string face = trim(entry.substr(0, colon));
          types::boundary_id id = numbers::invalid_boundary_id;
          for (unsigned int f = 0; f < 2 * dim; ++f)
            if (face == face_name(f))
              id = f;
          AssertThrow(id != numbers::invalid_boundary_id,
                      ExcMessage("Parameter 'Boundary conditions/Wall velocities': '" + face +
                                 "' is not a face of this box (x-, x+, y-, y+" +
                                 (dim == 3 ? ", z-, z+" : "") + ")."));
          AssertThrow(!periodic[id / 2],
                      ExcMessage("Parameter 'Boundary conditions/Wall velocities': face " +
                                 face + " lies in a periodic direction and is no wall."));
          wall_velocities[id] = to_tensor<dim>(entry.substr(colon + 1),
                                               "Boundary conditions/Wall velocities (" +
                                                 face + ")");
          AssertThrow(std::abs(wall_velocities[id][id / 2]) == 0.0,
                      ExcMessage("Parameter 'Boundary conditions/Wall velocities': wall " + face +
                                 " may only slide tangentially; its normal velocity must be 0."));
        }
    }
    prm.leave_subsection();
  }

  template <int dim>
  std::vector<typename Box<dim>::WallGap>
  Box<dim>::walls_near(const Point<dim> &x, const double r, const double reach) const
  {
    std::vector<WallGap> result;
    for (unsigned int d = 0; d < dim; ++d)
      if (!periodic[d])
        for (const int side : {-1, 1})
          {
            const double gap = (side < 0 ? x[d] - lower[d] : upper[d] - x[d]) - r;
            if (gap < reach)
              {
                WallGap wall{gap, Tensor<1, dim>(), wall_velocities[2 * d + (side > 0)]};
                wall.normal[d] = -side; // away from the wall, into the box
                result.push_back(wall);
              }
          }
    return result;
  }

  template <int dim>
  Tensor<1, dim> Box<dim>::period() const
  {
    Tensor<1, dim> L;
    for (unsigned int d = 0; d < dim; ++d)
      if (periodic[d])
        L[d] = upper[d] - lower[d];
    return L;
  }

  template <int dim>
  bool Box<dim>::is_wall(const types::boundary_id face) const
  {
    return face < 2 * dim && !periodic[face / 2];
  }

  template <int dim>
  Tensor<1, dim> Box<dim>::wall_velocity(const types::boundary_id face) const
  {
    return wall_velocities[face];
  }

  template <int dim>
  double Box<dim>::volume() const
  {
    double v = 1;
    for (unsigned int d = 0; d < dim; ++d)
      v *= upper[d] - lower[d];
    return v;
  }

  template <int dim>
  unsigned int Box<dim>::count_modes_below(const double k, const unsigned int cap) const
  {
    // Mode numbers m_0, …, m_{dim−1} direction by direction, each from 0 up while the
    // squared wavenumber so far stays below k²; a periodic m > 0 stands for ±m.
    std::array<double, dim> step;
    for (unsigned int d = 0; d < dim; ++d)
      step[d] = (periodic[d] ? 2 : 1) * numbers::PI / (upper[d] - lower[d]);
    unsigned int count = 0;
    const std::function<void(unsigned int, double, unsigned int, bool)> visit =
      [&](const unsigned int d, const double k2, const unsigned int multiplicity, const bool zero) {
        if (d == dim)
          {
            if (!zero)
              count = std::min(cap, count + multiplicity);
            return;
          }
        for (unsigned int m = 0; count < cap; ++m)
          {
            const double k2_m = k2 + std::pow(m * step[d], 2);
            if (!(k2_m < k * k))
              break;
            visit(d + 1, k2_m, multiplicity * (periodic[d] && m > 0 ? 2 : 1), zero && m == 0);
          }
      };
    visit(0, 0, 1, true);
    return count;
  }

  template class Box<2>;
  template class Box<3>;
} // namespace fdparticle
