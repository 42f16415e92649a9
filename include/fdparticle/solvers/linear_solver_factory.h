#ifndef fdparticle_solvers_linear_solver_factory_h
#define fdparticle_solvers_linear_solver_factory_h

#include <deal.II/base/parameter_handler.h>

#include <fdparticle/solvers/linear_solver.h>

#include <memory>

namespace fdparticle
{
  using namespace dealii;

  /// Declare the parameters of every LinearSolver implementation, and the choice between
  /// them (subsection Solver). A new solver adds its name to the selection here.
  void declare_linear_solver_parameters(ParameterHandler &prm);

  /// The implementation the parameters select, set up from them for a problem in dim
  /// space dimensions; 'auto' chooses by the number of finite-element unknowns.
  std::unique_ptr<LinearSolver> create_linear_solver(ParameterHandler &            prm,
                                                     const unsigned int            dim,
                                                     const types::global_dof_index unknowns);
} // namespace fdparticle

#endif
