// Simulation: what a step reports: the statistics of the fields and the output files.

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/introspection.h>

#include <algorithm>
#include <cmath>

namespace fdparticle
{
  template <int dim>
  double Simulation<dim>::max_velocity() const
  {
    double m = 0;
    for (const auto i : velocity_dofs)
      if (owned_dofs.is_element(i))
        m = std::max(m, std::abs(solution[i]));
    return Utilities::MPI::max(m, comm);
  }

  template <int dim>
  void Simulation<dim>::field_statistics()
  {
    // One pass over the cells for both field statistics of a step:
    //  - RMS over Ω of p − p_static minus its mean (zero for a fluid at hydrostatic rest);
    //  - (1/|Ω|) ∫_Ω u, the superficial velocity of the periodic-array problems.
    const FEValuesExtractors::Scalar pressure = Introspection<dim>::pressure();
    const FEValuesExtractors::Vector velocities = Introspection<dim>::velocities();
    const QGauss<dim>                q = Introspection<dim>::cell_quadrature();
    FEValues<dim> fv(assembler.get_mapping(), fe, q,
                     update_values | update_quadrature_points | update_JxW_values);
    std::vector<double>         p(q.size());
    std::vector<Tensor<1, dim>> u(q.size());
    // ∫ e, ∫ e², |Ω|, ∫ u_d.
    double               sums[3 + dim] = {};
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[pressure].get_function_values(solution_ghost, p);
          fv[velocities].get_function_values(solution_ghost, u);
          for (unsigned int qp = 0; qp < q.size(); ++qp)
            {
              const double e =
                p[qp] - fluid.hydrostatic_pressure(fv.quadrature_point(qp), pressure_reference_point);
              sums[0] += e * fv.JxW(qp);
              sums[1] += e * e * fv.JxW(qp);
              sums[2] += fv.JxW(qp);
              for (unsigned int d = 0; d < dim; ++d)
                sums[3 + d] += u[qp][d] * fv.JxW(qp);
            }
        }
    Utilities::MPI::sum(ArrayView<const double>(sums, 3 + dim), comm,
                        ArrayView<double>(sums, 3 + dim));
    const double mean = sums[0] / sums[2];
    statistics.set("hydrostatic_deviation",
                   std::sqrt(std::max(0.0, sums[1] / sums[2] - mean * mean)));
    Tensor<1, dim> mean_velocity;
    for (unsigned int d = 0; d < dim; ++d)
      mean_velocity[d] = sums[3 + d] / sums[2];
    statistics.set_vector("mean_v", mean_velocity);
  }

  template <int dim>
  void Simulation<dim>::write_output(const bool fields)
  {
    TimerOutput::Scope t(*timer, "output");
    output.write_particles_row(time.time(), particles);
    if (fields)
      output.write_fields(time.step_number(), time.time(), assembler.get_mapping(), dof_handler,
                          solution_ghost, assembler.particle_fraction(dof_handler), particles);
  }

  // The members defined in this file, for both dimensions (an explicit instantiation of a
  // class instantiates the members defined where it stands).
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace fdparticle
