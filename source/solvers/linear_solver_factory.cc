#include <fdparticle/base/parameter_tools.h>
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
      prm.declare_entry("Iterative solver from", "500000, 200000",
                        Patterns::List(Patterns::Double(0), 1, 2),
                        "Linear solver = auto: the number of finite-element unknowns from which "
                        "the iterative solver is used for the whole run: in 2D, in 3D (one "
                        "number: both). The defaults: in 2D where the direct solver needs a "
                        "quarter of a 24 GB machine; in 3D where the iterative one is faster on "
                        "a Stokes step and needs a quarter of the memory (doc/scaling.md).");
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
    const std::vector<std::string> thresholds =
      ParameterTools::split(prm.get("Iterative solver from"), ',');
    const double threshold = ParameterTools::to_double(
      thresholds[dim == 3 && thresholds.size() == 2 ? 1 : 0], "Solver/Iterative solver from");
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
