#include <fdparticle/solvers/direct_solver.h>
#include <fdparticle/solvers/linear_solver.h>

namespace fdparticle
{
  // One implementation so far: 'Solver/Linear solver' chooses among the direct solvers it
  // offers. A new implementation adds its names to that selection and its branch here.
  void LinearSolver::declare_parameters(ParameterHandler &prm)
  {
    DirectSolver::declare_parameters(prm);
  }

  std::unique_ptr<LinearSolver> LinearSolver::create(ParameterHandler &prm)
  {
    auto direct = std::make_unique<DirectSolver>();
    direct->parse_parameters(prm);
    return direct;
  }
} // namespace fdparticle
