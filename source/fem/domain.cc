#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <fdparticle/fem/domain.h>
#include <fdparticle/base/parameter_tools.h>

namespace fdparticle
{
  template <int dim>
  void Domain<dim>::declare_parameters(ParameterHandler &prm)
  {
    Box<dim>::declare_parameters(prm);
    prm.enter_subsection("Geometry");
    {
      prm.declare_entry("Subdivisions", "8, 16, 8", Patterns::Anything(),
                        "Base mesh cells per direction (Dimension integers >= 1).");
      prm.declare_entry("Global refinements", "0", Patterns::Integer(0, 12),
                        "Uniform refinements of the base mesh; each halves h.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void Domain<dim>::parse_parameters(ParameterHandler &prm)
  {
    using namespace ParameterTools;
    Box<dim>::parse_parameters(prm);
    prm.enter_subsection("Geometry");
    {
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
    GridGenerator::subdivided_hyper_rectangle(tria, subdivisions, this->lower, this->upper,
                                              /*colorize=*/true);
    std::vector<GridTools::PeriodicFacePair<
      typename parallel::distributed::Triangulation<dim>::cell_iterator>>
      pairs;
    for (unsigned int d = 0; d < dim; ++d)
      if (this->periodic[d])
        GridTools::collect_periodic_faces(tria, 2 * d, 2 * d + 1, d, pairs);
    if (!pairs.empty())
      tria.add_periodicity(pairs);
  }

  template <int dim>
  void Domain<dim>::create_coarsened_copy(const parallel::distributed::Triangulation<dim> &fine,
                                          parallel::distributed::Triangulation<dim> &coarse) const
  {
    coarse.copy_triangulation(fine);
    // The copy keeps p4est's periodic connectivity but not deal.II's map of periodic
    // faces, which the hanging-node and periodicity constraints read; p4est's
    // add_periodicity() needs an unrefined mesh, the base class's does not.
    std::vector<GridTools::PeriodicFacePair<
      typename parallel::distributed::Triangulation<dim>::cell_iterator>>
      pairs;
    for (unsigned int d = 0; d < dim; ++d)
      if (this->periodic[d])
        GridTools::collect_periodic_faces(coarse, 2 * d, 2 * d + 1, d, pairs);
    if (!pairs.empty())
      coarse.Triangulation<dim>::add_periodicity(pairs);
    coarse.coarsen_global();
  }

  template <int dim>
  void Domain<dim>::make_periodicity_constraints(const DoFHandler<dim> &    dof_handler,
                                                 AffineConstraints<double> &constraints) const
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (this->periodic[d])
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
          if (!this->is_wall(f))
            continue;
          const bool moving = this->wall_velocities[f].norm() > 0;
          if (moving != moving_pass)
            continue;
          if (moving && !homogeneous)
            {
              Vector<double> values(n_components);
              unsigned int   d = 0;
              for (unsigned int c = 0; c < n_components && d < dim; ++c)
                if (velocity_mask[c])
                  values[c] = this->wall_velocities[f][d++];
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
      h = std::min(h, (this->upper[d] - this->lower[d]) / subdivisions[d]);
    return h / std::pow(2.0, global_refinements);
  }

  template class Domain<2>;
  template class Domain<3>;
} // namespace fdparticle
