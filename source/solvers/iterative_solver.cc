#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <fdparticle/solvers/iterative_solver.h>

#include <sstream>
#include <iostream>

namespace fdparticle
{
  void IterativeSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    {
      prm.declare_entry("Max linear iterations", "500", Patterns::Integer(1),
                        "Iterative solver: FGMRES iterations after which a linear solve "
                        "counts as failed (the step is then retried with a smaller time step).");
      prm.declare_entry("Krylov basis size", "100", Patterns::Integer(2),
                        "Iterative solver: FGMRES restarts after this many iterations. Each "
                        "basis vector costs two vectors of the size of the system, allocated "
                        "only when used. A restart loses what the basis knew: 91 instead of "
                        "59 iterations with 50 on the 3D array of doc/scaling.md.");
      prm.declare_entry("Inner tolerance", "1e-3", Patterns::Double(0, 1),
                        "Iterative solver: relative tolerance of the inner solve of the "
                        "velocity, multiplier and particle unknowns in each application of "
                        "the preconditioner (doc/method.md §8).");
      prm.declare_entry("Cut cell patch layers", "-1", Patterns::Integer(-1, 3),
                        "Iterative solver: after each application of the block preconditioner, "
                        "solve exactly (UMFPACK, on each rank's own DoFs) for the velocity, "
                        "multiplier and pressure of the nearly covered cut cells (Cut cell "
                        "patch fluid fraction) and of this many rings of cells around them; "
                        "-1: no patch. With 1 the FGMRES iterations stop growing with "
                        "refinement (the cell-by-cell pressure approximation misses how a "
                        "cell that a particle almost covers couples to its neighbours), but "
                        "on meshes up to 200 000 unknowns the factored patch costs 1.4-1.8 "
                        "times the memory of the solver without it (doc/scaling.md).");
      prm.declare_entry("Cut cell patch fluid fraction", "0.25", Patterns::Double(0, 1),
                        "Iterative solver: only cut cells whose fluid part is at most this "
                        "fraction of the cell seed the cut-cell patch (with its rings): the "
                        "cells that a particle almost covers are where the cell-by-cell "
                        "pressure approximation fails. 0.25 keeps the FGMRES counts of the "
                        "whole shell (1) within 0-3 iterations with 20-60 % fewer patch "
                        "unknowns on the 3D scenes of doc/scaling.md; with 0.1 no cell of "
                        "the 3D array qualified at 8-10 cells per diameter.");
      prm.declare_entry("Iterative solver statistics", "false", Patterns::Bool(),
                        "Print, for every linear solve, the FGMRES iterations, the inner "
                        "iterations and the residual reached.");
      prm.declare_entry("Reuse preconditioner", "true", Patterns::Bool(),
                        "Iterative solver: keep the preconditioner for new Jacobians (Newton "
                        "iterations, time steps with the same mesh) while the iteration "
                        "count stays within 1.5 times that of its first solve.");
    }
    prm.leave_subsection();
  }

  void IterativeSolver::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    max_iterations = prm.get_integer("Max linear iterations");
    basis_size     = prm.get_integer("Krylov basis size");
    reuse          = prm.get_bool("Reuse preconditioner");
    preconditioner.inner_tolerance = prm.get_double("Inner tolerance");
    preconditioner.patch_layers    = prm.get_integer("Cut cell patch layers");
    preconditioner.patch_fluid_fraction = prm.get_double("Cut cell patch fluid fraction");
    verbose                        = prm.get_bool("Iterative solver statistics");
    prm.leave_subsection();
  }

  void IterativeSolver::pattern_changed()
  {
    preconditioner.clear();
    op.reset();
    stale = true;
  }

  void IterativeSolver::operator_changed()
  {
    if (!reuse)
      stale = true;
  }

  LinearSolver::SolveInfo IterativeSolver::solve(const NewtonSystem &system, const double tolerance,
                                                 TrilinosWrappers::MPI::Vector &x,
                                                 Eigen::VectorXd &              y)
  {
    if (!op || op->n_particle_unknowns() != system.D.rows())
      {
        op    = std::make_unique<BorderedOperator>(system);
        stale = true;
      }
    if (stale || !preconditioner.initialized())
      {
        preconditioner.initialize(system, *op);
        stale                = false;
        reference_iterations = 0;
      }

    const unsigned int            inner_before = preconditioner.inner_iterations();
    BorderedOperator::BlockVector rhs, solution;
    op->reinit_vector(rhs);
    op->reinit_vector(solution);
    {
      const double *r = system.r_fe.trilinos_vector()[0];
      double *      b = rhs.block(0).trilinos_vector()[0];
      for (int i = 0; i < rhs.block(0).trilinos_vector().MyLength(); ++i)
        b[i] = -r[i];
    }
    op->set_particle_part(rhs, -system.r_p);

    const double rhs_norm = rhs.l2_norm();
    SolverControl control(max_iterations, tolerance * rhs_norm, false, false);
    SolverFGMRES<BorderedOperator::BlockVector> fgmres(
      control, SolverFGMRES<BorderedOperator::BlockVector>::AdditionalData(basis_size));
    SolveInfo info;
    try
      {
        if (rhs_norm > 0)
          fgmres.solve(*op, solution, rhs, preconditioner);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        stale = true;
        std::ostringstream s;
        s << "the iterative linear solver did not converge in " << e.last_step
          << " iterations (relative residual " << e.last_residual / rhs_norm << ", target "
          << tolerance << ")";
        throw std::runtime_error(s.str());
      }
    info.iterations = control.last_step();
    info.residual   = rhs_norm > 0 ? control.last_value() / rhs_norm : 0;
    info.inner_iterations = preconditioner.inner_iterations() - inner_before;
    if (verbose && Utilities::MPI::this_mpi_process(system.r_fe.get_mpi_communicator()) == 0)
      std::cout << "  iterative solver: " << info.iterations << " FGMRES iterations ("
                << info.inner_iterations << " inner), relative residual " << info.residual << " for "
                << tolerance << "; cut-cell patch " << preconditioner.patch_size() << " unknowns"
                << std::endl;
    if (reference_iterations == 0)
      reference_iterations = std::max(1u, info.iterations);
    else if (info.iterations > rebuild_growth * reference_iterations)
      stale = true;

    x.reinit(system.r_fe.locally_owned_elements(), system.r_fe.get_mpi_communicator());
    x = solution.block(0);
    y = op->particle_part(solution);
    return info;
  }
} // namespace fdparticle
