// Simulation: the parameters of a run, the run itself and its time loop.

#include <deal.II/base/mpi.h>

#include <fdparticle/core/parameter_tools.h>
#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/introspection.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <iomanip>
#include <sstream>

namespace fdparticle
{
  namespace
  {
    /// Seconds as "42 s", "12 min" or "3.5 h", for the estimate of the time left.
    std::string format_duration(const double seconds)
    {
      std::ostringstream s;
      s << std::fixed;
      if (seconds < 120)
        s << std::setprecision(0) << seconds << " s";
      else if (seconds < 2 * 3600)
        s << std::setprecision(0) << seconds / 60 << " min";
      else
        s << std::setprecision(1) << seconds / 3600 << " h";
      return s.str();
    }

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
    LinearSolver::declare_parameters(prm);
    NewtonSolver::declare_parameters(prm);
    OutputWriter<3>::declare_parameters(prm);
    ParticleRefinement<3>::declare_parameters(prm);
    Checkpointer<3>::declare_parameters(prm);
    WallRepulsion<3>::declare_parameters(prm);
    Collisions<3>::declare_parameters(prm);
    Lubrication<3>::declare_parameters(prm);
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
    newton.parse_parameters(prm);
    output.parse_parameters(prm);
    refinement.parse_parameters(prm);
    {
      // Refused here, before the mesh is built: an unaffordable one fails by running out of
      // memory at an unpredictable point, on one rank only, or takes the machine down.
      const double cells = refinement.estimated_cells(domain, particles);
      AssertThrow(cells <= Domain<dim>::max_cells,
                  ExcMessage("The mesh would have about " + ParameterTools::format_short(cells) +
                             " cells (" + ParameterTools::format_short(domain.n_cells()) +
                             " base cells, Refinement/Particle refinement levels = " +
                             std::to_string(refinement.levels()) +
                             " around the particles); fdparticle refuses meshes of more than " +
                             ParameterTools::format_short(Domain<dim>::max_cells) +
                             " cells (0.1-1 TB of memory). Use fewer particle refinement "
                             "levels, a narrower Refinement/Band width or a coarser base mesh."));
      const double h = domain.base_cell_size() / std::pow(2.0, refinement.levels());
      for (unsigned int k = 0; k < particles.size(); ++k)
        AssertThrow(particles[k].radius >= ParticleSet<dim>::min_radius_in_cells * h,
                    ExcMessage("Particle " + std::to_string(k + 1) + " (radius " +
                               ParameterTools::format_short(particles[k].radius) +
                               ") is smaller than " +
                               ParameterTools::format_short(ParticleSet<dim>::min_radius_in_cells) +
                               " times the finest cell edge (h = " +
                               ParameterTools::format_short(h) +
                               "): the mesh cannot resolve it. Refine with Geometry/Global "
                               "refinements or Refinement/Particle refinement levels."));
    }
    checkpointer.parse_parameters(prm, output.directory());
    repulsion.parse_parameters(prm);
    collisions.parse_parameters(prm);
    lubrication.parse_parameters(prm);
    prm.enter_subsection("Initial conditions");
    hydrostatic_start = (prm.get("Pressure") == "hydrostatic");
    prm.leave_subsection();
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
      repulsion.initialize(domain, fluid, particles, finest_cell_size);
      collisions.initialize(domain, fluid, particles, finest_cell_size);
      lubrication.initialize(domain, fluid, finest_cell_size);
    }

    pcout << "fdparticle: " << dim << "D, " << triangulation.n_global_active_cells()
          << " cells, " << dof_handler.n_dofs() << " finite-element DoFs + "
          << particles.n_unknowns() << " particle unknowns, " << particles.size()
          << " particle(s), " << time.scheme_name() << ", "
          << (fluid.convection ? "Navier-Stokes" : "Stokes") << ", "
          << Utilities::MPI::n_mpi_processes(comm) << " MPI rank(s), "
          << (linear_solver->iterative() ? "iterative" : "direct") << " linear solver";
    pcout << partition_summary() << std::endl;
    check_resolution();
    for (const std::string &line :
         {repulsion.describe(time.next_step()), collisions.describe(time.next_step())})
      if (!line.empty())
        pcout << line << std::endl;

    // (simulated time, wall seconds) of the recent steps, for the estimate of the time left.
    std::deque<std::pair<double, double>> recent;
    while (!time.finished())
      {
        const double   step_start = wall_clock();
        StepStatistics stats;
        stats.step = time.step_number() + 1;
        do_time_step(stats);
        stats.time_step_reductions = time.reductions();
        smoothness.record(particles);
        time.advance();
        old_old_solution = old_solution;
        old_solution = solution;

        stats.time = time.time();
        stats.cells = triangulation.n_global_active_cells();
        stats.dofs = dof_handler.n_dofs() + particles.n_unknowns();
        stats.max_velocity = max_velocity();
        field_statistics(stats);
        collisions.statistics(particles, stats.contacts, stats.min_gap);
        stats.mean_particle_velocity = particles.mean_free_velocity();
        if (refinement.enabled())
          stats.coarse_cut_cells = refinement.coarse_cut_cells(triangulation, particles, base_level);
        write_output(output.vtu_due(time.step_number()));
        if (checkpointer.due(time.step_number()) || (checkpointer.enabled() && time.finished()))
          write_checkpoint();
        stats.wall_seconds = wall_clock() - step_start;
        output.write_statistics_row(stats);
        recent.emplace_back(stats.dt, stats.wall_seconds);
        if (recent.size() > progress_window)
          recent.pop_front();
        print_step_line(stats, recent);
      }
    smoothness.write(output.directory(), pcout, Utilities::MPI::this_mpi_process(comm) == 0);
    pcout << "fdparticle: done in " << std::setprecision(4) << wall_clock() - wall_start
          << " s; output in " << output.directory() << std::endl;
  }

  template <int dim>
  void Simulation<dim>::print_step_line(const StepStatistics &                        stats,
                                        const std::deque<std::pair<double, double>> &recent) const
  {
    double simulated = 0, wall = 0;
    for (const auto &[dt, seconds] : recent)
      {
        simulated += dt;
        wall += seconds;
      }
    const double end = time.end_time();
    const double left = (simulated > 0 ? (end - stats.time) * wall / simulated : 0.0);
    pcout << "step " << std::setw(5) << stats.step << "  t = " << std::setw(10)
          << std::setprecision(6) << stats.time << " / " << end << " (" << std::fixed
          << std::setprecision(0) << std::setw(3) << 100 * stats.time / end << " %)"
          << std::defaultfloat << "  Newton " << stats.nonlinear_iterations;
    if (linear_solver->iterative())
      pcout << "  linear " << stats.linear_iterations;
    pcout << "  residual "
          << std::scientific << std::setprecision(3) << stats.residual << std::defaultfloat
          << "  DoFs " << stats.dofs << "  " << std::setprecision(3) << stats.wall_seconds
          << " s";
    if (!time.finished())
      pcout << "  left ~" << format_duration(left);
    pcout << std::endl;
  }

  // The members defined in this file, for both dimensions.
  template Simulation<2>::Simulation(ParameterHandler &, const MPI_Comm);
  template void Simulation<2>::run();
  template void Simulation<2>::run_time_loop();
  template void Simulation<2>::print_step_line(const StepStatistics &, const std::deque<std::pair<double, double>> &) const;
  template Simulation<3>::Simulation(ParameterHandler &, const MPI_Comm);
  template void Simulation<3>::run();
  template void Simulation<3>::run_time_loop();
  template void Simulation<3>::print_step_line(const StepStatistics &, const std::deque<std::pair<double, double>> &) const;
} // namespace fdparticle
