// Simulation: the parameters of a run, the run itself and its time loop.

#include <deal.II/base/mpi.h>

#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/introspection.h>
#include <fdparticle/io/progress_line.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace fdparticle
{
  namespace
  {
    double wall_clock()
    {
      return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
    }

    void declare_simulation_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      {
        prm.declare_entry("Pressure", "zero", Patterns::Selection("zero|hydrostatic"),
                          "Initial pressure: zero, or hydrostatic (rho_f g + f).(x - x_ref), "
                          "x_ref the centre of the cell at the lower corner, where the pressure "
                          "level is fixed. Velocity, multiplier and particles start at rest.");
      }
      prm.leave_subsection();
    }
  } // namespace

  void declare_all_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Dimension", "3", Patterns::Integer(2, 3), "Space dimension, 2 or 3.");
    Domain<3>::declare_parameters(prm);
    Fluid<3>::declare_parameters(prm);
    ParticleSet<3>::declare_parameters(prm);
    TimeStepper::declare_parameters(prm);
    CutCellQuadrature<3>::declare_parameters(prm);
    NavierStokesAssembler<3>::declare_parameters(prm);
    PressureAgglomeration<3>::declare_parameters(prm);
    declare_linear_solver_parameters(prm);
    NewtonSolver::declare_parameters(prm);
    OutputWriter<3>::declare_parameters(prm);
    ParticleRefinement<3>::declare_parameters(prm);
    Checkpointer<3>::declare_parameters(prm);
    ParticleInteractions<3>::declare_parameters(prm);
    declare_simulation_parameters(prm);
  }

  template <int dim>
  Simulation<dim>::Simulation(ParameterHandler &prm, const MPI_Comm comm)
    : comm(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , prm(prm)
    , triangulation(comm,
                    typename Triangulation<dim>::MeshSmoothing(
                      Triangulation<dim>::limit_level_difference_at_vertices))
    , fe(Introspection<dim>::finite_element())
    , dof_handler(triangulation)
    , assembler(fe, fluid, particles, quadrature)
    , pressure_agglomeration(fe, assembler.get_mapping(), particles, quadrature)
  {
    domain.parse_parameters(prm);
    fluid.parse_parameters(prm);
    for (unsigned int d = 0; d < dim; ++d)
      fluid.periodic[d] = domain.is_periodic(d);
    particles.parse_parameters(prm, domain, comm);
    time.parse_parameters(prm);
    quadrature.parse_parameters(prm);
    if (quadrature.weighted_partition())
      triangulation.signals.weight.connect(
        [this](const typename Triangulation<dim>::cell_iterator &cell,
               const typename Triangulation<dim>::CellStatus) -> unsigned int {
          return quadrature.partition_weight(cell, particles);
        });
    assembler.parse_parameters(prm);
    pressure_agglomeration.parse_parameters(prm);
    newton.parse_parameters(prm);
    output.parse_parameters(prm);
    refinement.parse_parameters(prm);
    refinement.check_scene(domain, particles);
    checkpointer.parse_parameters(prm, output.directory());
    interactions.parse_parameters(prm);
    interactions.check_scene(particles);
    declare_statistics();
    prm.enter_subsection("Initial conditions");
    hydrostatic_start = (prm.get("Pressure") == "hydrostatic");
    prm.leave_subsection();
  }

  template <int dim>
  void Simulation<dim>::declare_statistics()
  {
    for (const char *name :
         {"step", "time", "dt", "cells", "dofs", "nonlinear_iterations", "linear_iterations",
          "inner_iterations", "residual", "initial_residual", "extrapolated_start", "jacobians",
          "solver_setups", "wall_seconds", "time_step_reductions", "max_velocity",
          "hydrostatic_deviation"})
      statistics.declare(name);
    statistics.declare_vector("mean_v");
    refinement.declare_columns(statistics);
    particles.declare_columns(statistics);
    interactions.declare_columns(statistics);
  }

  template <int dim>
  void Simulation<dim>::run()
  {
    // Created here, not in the constructor: an input error must not trigger its warnings.
    timer = std::make_unique<TimerOutput>(comm, pcout, TimerOutput::never,
                                                TimerOutput::wall_times);
    try
      {
        run_time_loop();
      }
    catch (...)
      {
        // Released inside the handler: a TimerOutput destroyed during unwinding prints a
        // warning about skipped MPI synchronisation after the one-line error.
        timer.reset();
        throw;
      }
    timer->print_summary();
    timer.reset();
  }

  template <int dim>
  void Simulation<dim>::run_time_loop()
  {
    wall_start = wall_clock();
    checkpointer.check_directory(comm);
    if (checkpointer.resume())
      resume();
    else
      start();
    {
      const double finest_cell_size = domain.base_cell_size() / std::pow(2.0, refinement.levels());
      interactions.initialize(domain, fluid, particles, finest_cell_size);
    }

    pcout << "fdparticle: " << dim << "D, " << triangulation.n_global_active_cells()
          << " cells, " << dof_handler.n_dofs() << " finite-element DoFs + "
          << particles.n_unknowns() << " particle unknowns, " << particles.size()
          << " particle(s), " << time.scheme_name() << ", "
          << (fluid.convection ? "Navier-Stokes" : "Stokes") << ", "
          << Utilities::MPI::n_mpi_processes(comm) << " MPI rank(s), "
          << linear_solver->name() << " linear solver";
    pcout << partition_summary() << std::endl;
    for (const std::string &line : refinement.resolution_warnings(triangulation, particles))
      pcout << line << std::endl;
    for (const std::string &line : interactions.describe(time.next_step()))
      pcout << line << std::endl;
    if (const std::string line = time.describe(); !line.empty())
      pcout << line << std::endl;

    ProgressLine progress(time.end_time(), linear_solver->iterative());
    while (!time.finished())
      {
        const double   step_start = wall_clock();
        statistics.new_row();
        statistics.set("step", time.step_number() + 1);
        do_time_step();
        statistics.set("time_step_reductions", time.reductions());
        smoothness.record(particles);
        time.advance();
        old_old_solution = old_solution;
        old_solution = solution;

        statistics.set("time", time.time());
        statistics.set("cells", triangulation.n_global_active_cells());
        statistics.set("dofs", dof_handler.n_dofs() + particles.n_unknowns());
        statistics.set("max_velocity", max_velocity());
        field_statistics();
        refinement.statistics(triangulation, particles, base_level, statistics);
        particles.statistics(statistics);
        interactions.statistics(particles, statistics);
        write_output(output.vtu_due(time.step_number()));
        if (checkpointer.due(time.step_number()) || (checkpointer.enabled() && time.finished()))
          write_checkpoint();
        statistics.set("wall_seconds", wall_clock() - step_start);
        output.write_statistics_row(statistics);
        progress.print(pcout, statistics, time.finished());
      }
    smoothness.write(output.directory(), pcout, Utilities::MPI::this_mpi_process(comm) == 0);
    pcout << "fdparticle: done in " << std::setprecision(4) << wall_clock() - wall_start
          << " s; output in " << output.directory() << std::endl;
  }

  // The members defined in this file, for both dimensions (an explicit instantiation of a
  // class instantiates the members defined where it stands).
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace fdparticle
