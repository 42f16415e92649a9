// Throughput of the velocity block of the Newton matrix, matrix-free (VelocityOperator)
// against the assembled sparse matrix (Trilinos/Epetra), on the same 3D mesh: the unit
// cube with N^3 cells, Q2 velocity, walls all round, Navier–Stokes coefficients (mass,
// viscous term, Newton's convection at a random iterate). Run by
// benchmarks/velocity_operator.sh, which states the regenerating command.
//
// Usage: velocity_operator_benchmark N [REPETITIONS]
// Prints one CSV row (without the header; see the script): ranks, cells, unknowns, the
// set-up and the best per-product seconds of each, their rates, and bytes per unknown.

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/vector_tools.h>

#include <fdparticle/fem/velocity_operator.h>

#include "velocity_matrix.h"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <random>

using namespace dealii;
using namespace fdparticle;

namespace
{
  constexpr int dim = 3;

  double now(const MPI_Comm comm)
  {
    MPI_Barrier(comm);
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  AssertThrow(argc >= 2, ExcMessage("Usage: velocity_operator_benchmark N [REPETITIONS]"));
  const unsigned int n    = std::atoi(argv[1]);
  const unsigned int reps = argc > 2 ? std::atoi(argv[2]) : 20;
  const double       density = 1, viscosity = 0.01, c0 = 150;

  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::subdivided_hyper_cube(tria, n);
  const FESystem<dim> fe(FE_Q<dim>(VelocityOperator<dim>::degree), dim);
  DoFHandler<dim>     dof_handler(tria);
  dof_handler.distribute_dofs(fe);
  const IndexSet owned = dof_handler.locally_owned_dofs();
  IndexSet       relevant;
  DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
  AffineConstraints<double> constraints(relevant);
  VectorTools::interpolate_boundary_values(dof_handler, 0, Functions::ZeroFunction<dim>(dim),
                                           constraints);
  constraints.close();
  const MappingQ<dim> mapping(1);

  // The random iterate w of the convection term, in both vector types.
  std::mt19937                           random(1);
  std::uniform_real_distribution<double> uniform(-1, 1);
  TrilinosWrappers::MPI::Vector          w(owned, comm), x(owned, comm), y(owned, comm);
  for (const auto i : owned)
    {
      w[i] = uniform(random);
      x[i] = uniform(random);
    }
  constraints.distribute(w);
  constraints.distribute(x);
  TrilinosWrappers::MPI::Vector w_ghosted(owned, relevant, comm);
  w_ghosted = w;

  // Matrix-free: set-up, then products.
  double                  start = now(comm);
  VelocityOperator<dim>   op;
  op.reinit(mapping, dof_handler, constraints);
  VelocityOperator<dim>::VectorType w_mf, x_mf, y_mf;
  op.initialize_dof_vector(w_mf);
  op.initialize_dof_vector(x_mf);
  op.initialize_dof_vector(y_mf);
  for (const auto i : owned)
    {
      w_mf[i] = w[i];
      x_mf[i] = x[i];
    }
  op.set_coefficients(density, viscosity, c0, &w_mf);
  const double mf_setup = now(comm) - start;
  double       mf_best  = 1e30;
  for (unsigned int r = 0; r < reps; ++r)
    {
      start = now(comm);
      op.vmult(y_mf, x_mf);
      mf_best = std::min(mf_best, now(comm) - start);
    }

  // Assembled: the same bilinear form by FEValues with the same Gauss rule.
  start = now(comm);
  TrilinosWrappers::SparseMatrix matrix;
  assemble_velocity_matrix(mapping, dof_handler, constraints, w_ghosted, density, viscosity, c0,
                           VelocityOperator<dim>::n_points_1d, matrix);
  const double matrix_setup = now(comm) - start;
  double       matrix_best  = 1e30;
  for (unsigned int r = 0; r < reps; ++r)
    {
      start = now(comm);
      matrix.vmult(y, x);
      matrix_best = std::min(matrix_best, now(comm) - start);
    }

  // The two agree on the unconstrained rows (a check that both apply the same operator).
  double largest = 0, difference = 0;
  for (const auto i : owned)
    if (!constraints.is_constrained(i))
      {
        largest    = std::max(largest, std::abs(y[i]));
        difference = std::max(difference, std::abs(y[i] - y_mf[i]));
      }
  largest    = Utilities::MPI::max(largest, comm);
  difference = Utilities::MPI::max(difference, comm);
  const double unknowns = dof_handler.n_dofs();
  const double matrix_bytes =
    Utilities::MPI::sum(double(matrix.memory_consumption()), comm) / unknowns;
  const double mf_bytes = double(op.memory_consumption()) / unknowns;
  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << Utilities::MPI::n_mpi_processes(comm) << ',' << tria.n_global_active_cells()
              << ',' << dof_handler.n_dofs() << ',' << std::setprecision(4) << mf_setup << ','
              << mf_best << ',' << matrix_setup << ',' << matrix_best << ','
              << unknowns / mf_best / 1e6 << ',' << unknowns / matrix_best / 1e6 << ','
              << matrix_best / mf_best << ',' << mf_bytes << ',' << matrix_bytes << ','
              << difference / largest << std::endl;
  // Printed first, so that a failed check still shows its numbers.
  AssertThrow(difference <= 1e-10 * largest,
              ExcMessage("matrix-free and assembled products differ by " +
                         std::to_string(difference / largest)));

}
