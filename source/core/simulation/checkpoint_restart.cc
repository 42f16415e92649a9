// Simulation: writing a checkpoint and resuming a run from one (Checkpointing/...).

#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/core/simulation.h>

#include <sstream>

namespace fdparticle
{
  template <int dim>
  void Simulation<dim>::resume()
  {
    std::string state;
    try
      {
        state = checkpointer.read_state(comm, particles.size());
      }
    catch (const std::exception &e)
      {
        throw CollectiveError(ParameterTools::one_line_message(e));
      }
    TimerOutput::Scope t(*timer, "checkpoint");
    domain.create_coarse_mesh(triangulation);
    checkpointer.load_mesh(triangulation);
    base_level = domain.n_global_refinements();
    setup_dofs();
    checkpointer.load_vectors(dof_handler, {&solution, &old_solution, &old_old_solution});
    solution_ghost = solution;
    std::istringstream in(state);
    time.load(in);
    particles.load(in);
    smoothness.load(in);
    output.load(in);
    if (in.fail())
      throw CollectiveError("The checkpoint in '" + checkpointer.directory() + "' is incomplete.");
    output.initialize(prm, statistics, comm, true, time.step_number(), time.time());
    pcout << "fdparticle: resumed from '" << checkpointer.directory() << "' at step "
          << time.step_number() << ", t = " << time.time() << std::endl;
  }

  template <int dim>
  void Simulation<dim>::write_checkpoint()
  {
    TimerOutput::Scope                         t(*timer, "checkpoint");
    std::vector<TrilinosWrappers::MPI::Vector> ghosted(3, solution_ghost);
    ghosted[0] = solution;
    ghosted[1] = old_solution;
    ghosted[2] = old_old_solution;
    std::ostringstream state;
    time.save(state);
    particles.save(state);
    smoothness.save(state);
    output.save(state);
    checkpointer.write(triangulation, dof_handler, {&ghosted[0], &ghosted[1], &ghosted[2]},
                       particles.size(), state.str());
  }

  // The members defined in this file, for both dimensions (an explicit instantiation of a
  // class instantiates the members defined where it stands).
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace fdparticle
