#include <fdparticle/solvers/direct_solver.h>
#include <fdparticle/solvers/iterative_solver.h>
#include <fdparticle/solvers/linear_solver.h>

namespace fdparticle
{
  void LinearSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    {
      prm.declare_entry("Linear solver", "direct", Patterns::Selection("direct|iterative|auto"),
                        "How the Newton system is solved (doc/method.md §8). 'direct': sparse "
                        "factorization (Direct solver) and the particle unknowns by their "
                        "Schur complement; exact, time and memory growing faster than the "
                        "unknowns. 'iterative': FGMRES with a block preconditioner; memory "
                        "linear in the unknowns, to the Newton tolerance (inexact Newton). "
                        "'auto': iterative when the mesh a run starts (or resumes) with has at least 'Iterative solver "
                        "from' finite-element unknowns, else direct (kept for the whole run).");
      prm.declare_entry("Iterative solver from", "500000", Patterns::Double(0),
                        "Linear solver = auto: the problem size (unknowns) from which the "
                        "iterative solver is used. The default is where the direct solver "
                        "needs more than a quarter of a 24 GB machine in 3D; the iterative "
                        "solver is as fast from about 100 k unknowns on the steady 3D array and "
                        "450 k on the 3D sediment step, with half the memory (doc/scaling.md).");
    }
    prm.leave_subsection();
    DirectSolver::declare_parameters(prm);
    IterativeSolver::declare_parameters(prm);
  }

  std::unique_ptr<LinearSolver> LinearSolver::create(ParameterHandler &prm,
                                                     const types::global_dof_index unknowns)
  {
    prm.enter_subsection("Solver");
    std::string choice = prm.get("Linear solver");
    const double threshold = prm.get_double("Iterative solver from");
    prm.leave_subsection();
    if (choice == "auto")
      choice = unknowns >= threshold ? "iterative" : "direct";
    if (choice == "iterative")
      {
        auto iterative = std::make_unique<IterativeSolver>();
        iterative->parse_parameters(prm);
        return iterative;
      }
    auto direct = std::make_unique<DirectSolver>();
    direct->parse_parameters(prm);
    return direct;
  }
} // namespace fdparticle
