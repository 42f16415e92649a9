// Unit test of the choice between the linear solvers (source/solvers/linear_solver_factory.cc),
// read from a ParameterHandler as the program reads it (subsection Solver): 'direct' and
// 'iterative' whatever the size; 'auto' iterative from 'Iterative solver from' unknowns, whose
// first number holds in 2D and second in 3D, a single number in both.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <fdparticle/solvers/direct_solver.h>
#include <fdparticle/solvers/iterative_solver.h>
#include <fdparticle/solvers/linear_solver_factory.h>

#include "unit_check.h"

#include <string>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  /// Whether the solver chosen for the given entries, dimension and size is the iterative one.
  bool iterative(const std::string &choice, const std::string &from, const unsigned int dim,
                 const types::global_dof_index unknowns)
  {
    ParameterHandler prm;
    declare_linear_solver_parameters(prm);
    std::string input = "subsection Solver\n  set Linear solver = " + choice + "\n";
    if (!from.empty())
      input += "  set Iterative solver from = " + from + "\n";
    prm.parse_input_from_string(input + "end\n");
    const auto solver = create_linear_solver(prm, dim, unknowns);
    return dynamic_cast<const IterativeSolver *>(solver.get()) != nullptr;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  check(!iterative("direct", "", 3, 100000000), "direct stays direct at any size");
  check(iterative("iterative", "", 2, 10), "iterative stays iterative at any size");

  // The defaults: 500 000 in 2D, 200 000 in 3D.
  check(!iterative("auto", "", 2, 499999), "auto, 2D, default: direct below 500 000");
  check(iterative("auto", "", 2, 500000), "auto, 2D, default: iterative from 500 000");
  check(!iterative("auto", "", 3, 199999), "auto, 3D, default: direct below 200 000");
  check(iterative("auto", "", 3, 200000), "auto, 3D, default: iterative from 200 000");

  // Two numbers: the first in 2D, the second in 3D.
  check(iterative("auto", "1000, 1e9", 2, 5000), "auto, 2D reads the first number");
  check(!iterative("auto", "1000, 1e9", 3, 5000), "auto, 3D does not read the first number");
  check(iterative("auto", "1e9, 1000", 3, 5000), "auto, 3D reads the second number");
  check(!iterative("auto", "1e9, 1000", 2, 5000), "auto, 2D does not read the second number");

  // One number: both dimensions.
  check(iterative("auto", "1000", 2, 5000) && iterative("auto", "1000", 3, 5000),
        "auto, one number holds in 2D and 3D");
  check(!iterative("auto", "1e9", 2, 5000) && !iterative("auto", "1e9", 3, 5000),
        "auto, one large number: direct in 2D and 3D");

  return summary();
}
