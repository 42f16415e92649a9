#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <fdparticle/fem/domain.h>
#include <fdparticle/core/parameter_tools.h>

namespace fdparticle
{
  template <int dim>
  void Domain<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    {
      prm.declare_entry("Lower corner", "-0.5, -0.5, -0.5", Patterns::Anything(),
                        "Lower corner of the box, Dimension comma-separated numbers.");
      prm.declare_entry("Upper corner", "0.5, 1.5, 0.5", Patterns::Anything(),
                        "Upper corner of the box; every coordinate above the lower corner's.");
      prm.declare_entry("Subdivisions", "8, 16, 8", Patterns::Anything(),
                        "Base mesh cells per direction (Dimension integers >= 1).");
      prm.declare_entry("Global refinements", "0", Patterns::Integer(0, 12),
                        "Uniform refinements of the base mesh; each halves h.");
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
  std::string Domain<dim>::face_name(const types::boundary_id face)
  {
    return std::string(1, "xyz"[face / 2]) + (face % 2 == 0 ? "-" : "+");
  }

  template <int dim>
  void Domain<dim>::parse_parameters(ParameterHandler &prm)
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
      const Tensor<1, dim> n = get_tensor<dim>(prm, "Subdivisions", "Geometry/Subdivisions");
      subdivisions.resize(dim);
      global_refinements = prm.get_integer("Global refinements");
      double cells = std::pow(2.0, dim * global_refinements);
      for (unsigned int d = 0; d < dim; ++d)
        {
          AssertThrow(n[d] >= 1 && n[d] == std::floor(n[d]),
                      ExcMessage("Parameter 'Geometry/Subdivisions' needs integers >= 1, got " +
                                 prm.get("Subdivisions") + "."));
          cells *= n[d];
        }
      // Checked in floating point before the conversion, which wraps around above 2^32.
      AssertThrow(cells <= max_cells,
                  ExcMessage("Parameters 'Geometry/Subdivisions' = " + prm.get("Subdivisions") +
                             " and 'Geometry/Global refinements' = " +
                             prm.get("Global refinements") + " ask for " + format_short(cells) +
                             " cells; fdparticle refuses meshes of more than " +
                             format_short(max_cells) +
                             " cells (0.1-1 TB of memory). Use fewer subdivisions or "
                             "refinements."));
      for (unsigned int d = 0; d < dim; ++d)
        subdivisions[d] = static_cast<unsigned int>(n[d]);
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
  void Domain<dim>::create_mesh(parallel::distributed::Triangulation<dim> &tria) const
  {
    create_coarse_mesh(tria);
    tria.refine_global(global_refinements);
  }

  template <int dim>
  void Domain<dim>::create_coarse_mesh(parallel::distributed::Triangulation<dim> &tria) const
  {
    GridGenerator::subdivided_hyper_rectangle(tria, subdivisions, lower, upper,
                                              /*colorize=*/true);
    std::vector<GridTools::PeriodicFacePair<
      typename parallel::distributed::Triangulation<dim>::cell_iterator>>
      pairs;
    for (unsigned int d = 0; d < dim; ++d)
      if (periodic[d])
        GridTools::collect_periodic_faces(tria, 2 * d, 2 * d + 1, d, pairs);
    if (!pairs.empty())
      tria.add_periodicity(pairs);
  }

  template <int dim>
  void Domain<dim>::make_periodicity_constraints(const DoFHandler<dim> &    dof_handler,
                                                 AffineConstraints<double> &constraints) const
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (periodic[d])
        DoFTools::make_periodicity_constraints(dof_handler, 2 * d, 2 * d + 1, d, constraints);
  }

  template <int dim>
  void Domain<dim>::make_wall_constraints(const DoFHandler<dim> &    dof_handler,
                                          const ComponentMask &      velocity_mask,
                                          const bool                 homogeneous,
                                          AffineConstraints<double> &constraints) const
  {
    const unsigned int n_components = dof_handler.get_fe().n_components();
    const Functions::ZeroFunction<dim> zero(n_components);
    // Resting walls first: interpolate_boundary_values leaves constrained DoFs alone.
    for (const bool moving_pass : {false, true})
      for (types::boundary_id f = 0; f < 2 * dim; ++f)
        {
          if (!is_wall(f))
            continue;
          const bool moving = wall_velocities[f].norm() > 0;
          if (moving != moving_pass)
            continue;
          if (moving && !homogeneous)
            {
              Vector<double> values(n_components);
              unsigned int   d = 0;
              for (unsigned int c = 0; c < n_components && d < dim; ++c)
                if (velocity_mask[c])
                  values[c] = wall_velocities[f][d++];
              VectorTools::interpolate_boundary_values(
                dof_handler, f, Functions::ConstantFunction<dim>(values), constraints,
                velocity_mask);
            }
          else
            VectorTools::interpolate_boundary_values(dof_handler, f, zero, constraints,
                                                     velocity_mask);
        }
  }

  template <int dim>
  std::vector<typename Domain<dim>::WallGap>
  Domain<dim>::walls_near(const Point<dim> &x, const double r, const double reach) const
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
  bool Domain<dim>::is_periodic(const unsigned int direction) const
  {
    return periodic[direction];
  }

  template <int dim>
  Tensor<1, dim> Domain<dim>::period() const
  {
    Tensor<1, dim> L;
    for (unsigned int d = 0; d < dim; ++d)
      if (periodic[d])
        L[d] = upper[d] - lower[d];
    return L;
  }

  template <int dim>
  bool Domain<dim>::is_wall(const types::boundary_id face) const
  {
    return face < 2 * dim && !periodic[face / 2];
  }

  template <int dim>
  Tensor<1, dim> Domain<dim>::wall_velocity(const types::boundary_id face) const
  {
    return wall_velocities[face];
  }

  template <int dim>
  double Domain<dim>::volume() const
  {
    double v = 1;
    for (unsigned int d = 0; d < dim; ++d)
      v *= upper[d] - lower[d];
    return v;
  }

  template <int dim>
  double Domain<dim>::n_cells() const
  {
    double n = std::pow(2.0, dim * global_refinements);
    for (const unsigned int s : subdivisions)
      n *= s;
    return n;
  }

  template <int dim>
  double Domain<dim>::base_cell_size() const
  {
    double h = std::numeric_limits<double>::max();
    for (unsigned int d = 0; d < dim; ++d)
      h = std::min(h, (upper[d] - lower[d]) / subdivisions[d]);
    return h / std::pow(2.0, global_refinements);
  }

  template class Domain<2>;
  template class Domain<3>;
} // namespace fdparticle
