// The velocity block's inverse approximated by a geometric multigrid V-cycle on the
// matrix-free operator (VelocityOperator on every level, Chebyshev smoothing on its
// diagonal, transfer between levels by MGTransferMatrixFree) against one V-cycle of ML on
// the assembled matrix, the way the block preconditioner uses it: GMRES on A_uu x = b to
// 1e-8 with each as preconditioner. The unit cube with N0^3 cells refined L times, Q2
// velocity, walls all round, Navier–Stokes coefficients (mass, viscous term, Newton's
// convection at a smooth iterate). Run by benchmarks/velocity_multigrid.sh.
//
// Usage: velocity_multigrid_benchmark N0 L
// Prints one CSV row: ranks, cells, unknowns, then for GMG and for ML the set-up seconds,
// the GMRES iterations and the solve seconds.

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/multigrid/mg_coarse.h>
#include <deal.II/multigrid/mg_constrained_dofs.h>
#include <deal.II/multigrid/mg_matrix.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/mg_tools.h>
#include <deal.II/multigrid/mg_transfer_matrix_free.h>
#include <deal.II/multigrid/multigrid.h>
#include <deal.II/numerics/vector_tools.h>

#include <fdparticle/fem/velocity_operator.h>

#include "velocity_matrix.h"

#include <chrono>
#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace fdparticle;

namespace
{
  constexpr int dim = 3;
  using Operator   = VelocityOperator<dim>;
  using VectorType = Operator::VectorType;

  double now(const MPI_Comm comm)
  {
    MPI_Barrier(comm);
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
  }

  /// A smooth iterate w: a vortex of unit size.
  class Vortex : public Function<dim>
  {
  public:
    Vortex()
      : Function<dim>(dim)
    {}
    double value(const Point<dim> &p, const unsigned int c) const override
    {
      const double s = std::sin(numbers::PI * p[0]) * std::sin(numbers::PI * p[1]) *
                       std::sin(numbers::PI * p[2]);
      return c == 0 ? s * p[1] : (c == 1 ? -s * p[0] : 0.3 * s);
    }
  };

  /// The level operators' Chebyshev smoothers need a DiagonalMatrix of the inverse diagonal.
  std::shared_ptr<DiagonalMatrix<VectorType>> inverse_diagonal(const Operator &op)
  {
    auto inverse = std::make_shared<DiagonalMatrix<VectorType>>();
    op.compute_diagonal(inverse->get_vector());
    for (auto &entry : inverse->get_vector())
      entry = 1. / entry;
    return inverse;
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  AssertThrow(argc >= 3, ExcMessage("Usage: velocity_multigrid_benchmark N0 L"));
  const unsigned int n0 = std::atoi(argv[1]), n_refinements = std::atoi(argv[2]);
  const double       density = 1, viscosity = 0.01, c0 = 150;
  const double       tolerance = 1e-8;

  parallel::distributed::Triangulation<dim> tria(
    comm, Triangulation<dim>::limit_level_difference_at_vertices,
    parallel::distributed::Triangulation<dim>::construct_multigrid_hierarchy);
  GridGenerator::subdivided_hyper_cube(tria, n0);
  tria.refine_global(n_refinements);
  const FESystem<dim> fe(FE_Q<dim>(Operator::degree), dim);
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

  // The iterate on the active mesh and the right-hand side b = A (1, 1, 1).
  Operator op;
  op.reinit(mapping, dof_handler, constraints);
  VectorType w, x, b;
  op.initialize_dof_vector(w);
  op.initialize_dof_vector(x);
  op.initialize_dof_vector(b);
  VectorTools::interpolate(mapping, dof_handler, Vortex(), w);
  constraints.distribute(w);
  op.set_coefficients(density, viscosity, c0, &w);
  {
    VectorType ones;
    op.initialize_dof_vector(ones);
    ones = 1;
    constraints.set_zero(ones);
    op.vmult(b, ones);
  }

  // Geometric multigrid: level operators, transfer, Chebyshev smoothing.
  double start = now(comm);
  dof_handler.distribute_mg_dofs();
  MGConstrainedDoFs mg_constrained_dofs;
  mg_constrained_dofs.initialize(dof_handler);
  mg_constrained_dofs.make_zero_boundary_constraints(dof_handler, {0});
  const unsigned int      n_levels = tria.n_global_levels();
  MGLevelObject<Operator> level_operators(0, n_levels - 1);
  MGLevelObject<VectorType> level_iterate(0, n_levels - 1);
  for (unsigned int level = 0; level < n_levels; ++level)
    {
      IndexSet level_relevant;
      DoFTools::extract_locally_relevant_level_dofs(dof_handler, level, level_relevant);
      AffineConstraints<double> level_constraints(level_relevant);
      level_constraints.add_lines(mg_constrained_dofs.get_boundary_indices(level));
      level_constraints.close();
      level_operators[level].reinit(mapping, dof_handler, level_constraints, level);
      level_operators[level].initialize_dof_vector(level_iterate[level]);
    }
  // The transfer's level vectors with the level operators' layouts (ghosts included).
  MGTransferMatrixFree<dim, double> transfer(mg_constrained_dofs);
  {
    std::vector<std::shared_ptr<const Utilities::MPI::Partitioner>> partitioners(n_levels);
    for (unsigned int level = 0; level < n_levels; ++level)
      partitioners[level] = level_operators[level].get_matrix_free().get_vector_partitioner();
    transfer.build(dof_handler, partitioners);
  }
  transfer.interpolate_to_mg(dof_handler, level_iterate, w);
  using Smoother = PreconditionChebyshev<Operator, VectorType>;
  mg::SmootherRelaxation<Smoother, VectorType> smoother;
  MGLevelObject<typename Smoother::AdditionalData> smoother_data(0, n_levels - 1);
  for (unsigned int level = 0; level < n_levels; ++level)
    {
      level_operators[level].set_coefficients(density, viscosity, c0, &level_iterate[level]);
      smoother_data[level].preconditioner  = inverse_diagonal(level_operators[level]);
      smoother_data[level].smoothing_range = 15;
      smoother_data[level].degree          = level > 0 ? 4 : numbers::invalid_unsigned_int;
      smoother_data[level].eig_cg_n_iterations = 12;
      smoother_data[level].eigenvalue_algorithm =
        Smoother::AdditionalData::EigenvalueAlgorithm::power_iteration;
    }
  smoother.initialize(level_operators, smoother_data);
  MGCoarseGridApplySmoother<VectorType> coarse(smoother);
  mg::Matrix<VectorType>                level_matrix(level_operators);
  Multigrid<VectorType> multigrid(level_matrix, coarse, transfer, smoother, smoother);
  PreconditionMG<dim, VectorType, MGTransferMatrixFree<dim, double>> gmg(dof_handler, multigrid,
                                                                          transfer);
  const double gmg_setup = now(comm) - start;

  start = now(comm);
  SolverControl gmg_control(500, tolerance * b.l2_norm());
  {
    SolverGMRES<VectorType> gmres(gmg_control);
    x = 0;
    gmres.solve(op, x, b, gmg);
  }
  const double gmg_solve = now(comm) - start;

  // ML on the assembled matrix, as the block preconditioner sets it up.
  start = now(comm);
  TrilinosWrappers::SparseMatrix matrix;
  w.update_ghost_values();
  assemble_velocity_matrix(mapping, dof_handler, constraints, w, density, viscosity, c0,
                           Operator::n_points_1d, matrix);
  const double assembly = now(comm) - start;
  start                 = now(comm);
  TrilinosWrappers::PreconditionAMG::AdditionalData amg;
  amg.elliptic              = true;
  amg.higher_order_elements = true;
  DoFTools::extract_constant_modes(dof_handler, ComponentMask(dim, true), amg.constant_modes);
  amg.smoother_sweeps       = 1;
  amg.aggregation_threshold = 0.02;
  TrilinosWrappers::PreconditionAMG ml;
  ml.initialize(matrix, amg);
  const double ml_setup = now(comm) - start;
  TrilinosWrappers::MPI::Vector b_t(owned, comm), x_t(owned, comm);
  for (const auto i : owned)
    b_t[i] = b[i];
  start = now(comm);
  SolverControl ml_control(500, tolerance * b_t.l2_norm());
  {
    SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(ml_control);
    gmres.solve(matrix, x_t, b_t, ml);
  }
  const double ml_solve = now(comm) - start;

  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << Utilities::MPI::n_mpi_processes(comm) << ',' << tria.n_global_active_cells()
              << ',' << dof_handler.n_dofs() << ',' << n_levels << ',' << std::setprecision(4)
              << gmg_setup << ',' << gmg_control.last_step() << ',' << gmg_solve << ','
              << assembly << ',' << ml_setup << ',' << ml_control.last_step() << ','
              << ml_solve << std::endl;
}
