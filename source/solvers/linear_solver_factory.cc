#include <fdparticle/solvers/direct_solver.h>
#include <fdparticle/solvers/iterative_solver.h>
#include <fdparticle/solvers/linear_solver_factory.h>

namespace fdparticle
{
  void declare_linear_solver_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    {
      prm.declare_entry("Linear solver", "direct", Patterns::Selection("direct|iterative|auto"),
                        "How the Newton system is solved (doc/method.md §8). direct: sparse "
                        "factorization, exact; time and memory grow faster than the unknowns. "
                        "iterative: FGMRES with a block preconditioner, memory linear in the "
                        "unknowns. auto: iterative if the first mesh of a run (or resume) has at "
                        "least 'Iterative solver from' unknowns.");
      prm.declare_entry("Iterative solver from", "500000", Patterns::Double(0),
                        "Linear solver = auto: the number of finite-element unknowns from which "
                        "the iterative solver is used for the whole run. The default is where the "
                        "direct solver needs a quarter of a 24 GB machine in 3D; lower it to save "
                        "memory (doc/scaling.md).");
    }
    prm.leave_subsection();
    DirectSolver::declare_parameters(prm);
    IterativeSolver::declare_parameters(prm);
  }

  std::unique_ptr<LinearSolver> create_linear_solver(ParameterHandler &            prm,
                                                     const unsigned int            dim,
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
    direct->parse_parameters(prm, dim);
    return direct;
  }
} // namespace fdparticle
