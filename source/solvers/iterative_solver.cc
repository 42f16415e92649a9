#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <fdparticle/solvers/free_unknowns.h>
#include <fdparticle/solvers/iterative_solver.h>

#include <cmath>
#include <iostream>
#include <sstream>

namespace fdparticle
{
  void IterativeSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    {
      prm.declare_entry("Max linear iterations", "500", Patterns::Integer(1),
                        "Iterative solver: outer Krylov iterations after which a linear solve "
                        "counts as failed (the step is then retried with a smaller time step).");
      prm.declare_entry("Krylov basis size", "100", Patterns::Integer(2),
                        "Iterative solver: GMRES and FGMRES restart after this many iterations. "
                        "Each basis vector costs one vector of the unconstrained unknowns with "
                        "the cheap preconditioner (GMRES), two with the inner solve (FGMRES), allocated only "
                        "when used; "
                        "a restart loses what the basis knew and costs iterations, so raise it "
                        "together with Cheap iterations (doc/scaling.md).");
      prm.declare_entry("Cheap iterations", "100", Patterns::Integer(0),
                        "Iterative solver: GMRES iterations tried first with the cheap "
                        "preconditioner (no inner solve, doc/method.md §8); if they miss the "
                        "tolerance the solve continues with the inner solve (FGMRES). 0: always the inner "
                        "solve. Raise it, with Krylov basis size, when solves fall back, as for "
                        "close pairs (doc/scaling.md).");
      prm.declare_entry("Inner tolerance", "1e-3", Patterns::Double(0, 1),
                        "Iterative solver: relative tolerance of the inner solve of the "
                        "velocity, multiplier and particle unknowns in each application of "
                        "the preconditioner (doc/method.md §8).");
      prm.declare_entry("Cut cell patch layers", "1", Patterns::Integer(-1, 3),
                        "Iterative solver: after each preconditioner application, solve exactly "
                        "(MUMPS, all ranks) for the cells inside the particles, the nearly "
                        "covered cut cells and this many rings around them (doc/method.md §8). 1 "
                        "keeps the outer iterations from growing with refinement. -1: no patch, "
                        "for suspensions short of memory (doc/scaling.md).");
      prm.declare_entry("Cut cell patch memory", "4", Patterns::Double(0),
                        "Iterative solver: largest memory, in GB per rank, that the factorization "
                        "of the cut-cell patch may take, by MUMPS's estimate before factoring; a "
                        "larger patch is dropped with one warning and the solve goes on without "
                        "it, with more iterations. 0: no limit. Raise it on machines with more "
                        "memory (doc/scaling.md).");
      prm.declare_entry("Cut cell patch fluid fraction", "0.25", Patterns::Double(0, 1),
                        "Iterative solver: only cut cells whose fluid part is at most this "
                        "fraction of the cell seed the cut-cell patch: where a particle almost "
                        "covers a cell the cell-by-cell pressure approximation fails. 0.25 keeps "
                        "the iterations of the whole shell (1) with fewer patch unknowns "
                        "(doc/scaling.md).");
      prm.declare_entry("Cut cell patch symmetric part", "true", Patterns::Bool(),
                        "Iterative solver: where convection makes the cut-cell patch "
                        "non-symmetric (Navier-Stokes once the fluid moves), factor its "
                        "symmetric part (LDL^T) instead of the patch itself (LU): about 0.65 "
                        "of LU's factor memory for the same iterations on the scenes of "
                        "doc/scaling.md; the correction's residual stays exact. false: LU, "
                        "for flows where convection dominates the cells around a particle.");
      prm.declare_entry("Velocity preconditioner", "multigrid", Patterns::Selection("amg|multigrid"),
                        "Iterative solver: the approximate inverse of the velocity block inside "
                        "the block preconditioner (doc/method.md §8). multigrid: one geometric "
                        "multigrid V-cycle on the matrix-free velocity operator over the mesh "
                        "coarsened level by level down to the base mesh, then linear elements "
                        "there, ML on those; no velocity matrix, also not in the Newton "
                        "matrix (its products are matrix-free), 1.1-1.9 times faster than amg "
                        "(doc/scaling.md). amg: one ML V-cycle on the assembled velocity "
                        "matrix.");
      prm.declare_entry("Pressure Laplacian", "auto", Patterns::Selection("auto|true|false"),
                        "Iterative solver: the inertial term -rho_f c0 L^-1 of the pressure "
                        "Schur complement's inverse (Cahouet-Chabard; L = G M_u^-1 G^T, one "
                        "AMG V-cycle; doc/method.md §8). It matters for the pressure modes of "
                        "the box whose wavenumber is below sqrt(rho_f c0/mu), where inertia "
                        "outweighs viscosity (small time steps, small viscosity). auto: left "
                        "out when there are at most 10 such modes and each spans about 20 or "
                        "more of the base mesh's cells (sqrt(rho_f c0/mu) h <= 0.3): GMRES "
                        "then resolves them in about as many iterations, which costs less "
                        "than L's set-up and V-cycles (doc/scaling.md).");
      prm.declare_entry("Iterative solver statistics", "false", Patterns::Bool(),
                        "Print, for every linear solve, the outer and inner iterations, the "
                        "residual reached, the cut-cell patch's size and memory, and rank 0's "
                        "wall times of building the preconditioner and of iterating, each split "
                        "into its main parts.");
      prm.declare_entry("Reuse preconditioner", "true", Patterns::Bool(),
                        "Iterative solver: keep the preconditioner for new Jacobians (Newton "
                        "iterations, time steps on the same mesh) until a solve needs more than "
                        "1.5 times the outer iterations per tenfold residual reduction of the "
                        "slowest solve with its own Jacobian (doc/method.md §8). false: a new "
                        "preconditioner for every Jacobian.");
    }
    prm.leave_subsection();
  }

  void IterativeSolver::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    max_iterations = prm.get_integer("Max linear iterations");
    cheap_iterations = prm.get_integer("Cheap iterations");
    basis_size     = prm.get_integer("Krylov basis size");
    reuse          = prm.get_bool("Reuse preconditioner");
    preconditioner.inner_tolerance = prm.get_double("Inner tolerance");
    preconditioner.patch_layers    = prm.get_integer("Cut cell patch layers");
    preconditioner.patch_fluid_fraction = prm.get_double("Cut cell patch fluid fraction");
    preconditioner.patch_memory_limit   = prm.get_double("Cut cell patch memory") * 1e9;
    preconditioner.symmetrize_patch     = prm.get_bool("Cut cell patch symmetric part");
    verbose                        = prm.get_bool("Iterative solver statistics");
    velocity_multigrid             = prm.get("Velocity preconditioner") == "multigrid";
    const std::string inertia      = prm.get("Pressure Laplacian");
    preconditioner.inertia         = inertia == "true"  ? BlockPreconditioner::Inertia::always :
                                     inertia == "false" ? BlockPreconditioner::Inertia::never :
                                                          BlockPreconditioner::Inertia::automatic;
    prm.leave_subsection();
  }

  void IterativeSolver::pattern_changed()
  {
    preconditioner.clear();
    op.reset();
    stale = true;
    velocity_nonzeros = numbers::invalid_dof_index;
  }

  void IterativeSolver::operator_changed()
  {
    // A preconditioner is rebuilt only for a new Jacobian: the one it was built for cannot
    // get a better one.
    if (!reuse || drifted)
      stale = true;
    fresh = false;
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
    bool rebuilt = false;
    const auto rebuild = [&]() {
      preconditioner.initialize(system, *op);
      stale          = false;
      fresh          = true;
      drifted        = false;
      reference_rate = 0;
      cheap_failed   = false;
      rebuilt        = true;
    };
    if (stale || !preconditioner.initialized())
      rebuild();

    const Timer                   iteration_timer;
    const double products_before = op->vmult_time();
    // This solve's inner iterations and preconditioner times; the preconditioner counts
    // from its last build, which may come in the middle of the solve.
    unsigned int                          inner = 0;
    BlockPreconditioner::ApplicationTimes parts;
    unsigned int                          inner_before = preconditioner.inner_iterations();
    BlockPreconditioner::ApplicationTimes parts_before = preconditioner.application_times();
    const auto count = [&]() {
      const BlockPreconditioner::ApplicationTimes &now = preconditioner.application_times();
      inner += preconditioner.inner_iterations() - inner_before;
      parts.velocity_cycles += now.velocity_cycles - parts_before.velocity_cycles;
      parts.multiplier_cycles += now.multiplier_cycles - parts_before.multiplier_cycles;
      parts.particle_block += now.particle_block - parts_before.particle_block;
      inner_before = preconditioner.inner_iterations();
      parts_before = now;
    };
    // The Krylov vectors hold the free unknowns only.
    const FreeUnknowns                        free(*op, system);
    const OnFreeUnknowns<BorderedOperator>    matrix{free, *op};
    const OnFreeUnknowns<BlockPreconditioner> preconditioned{free, preconditioner};
    BorderedOperator::BlockVector rhs, solution;
    {
      BorderedOperator::BlockVector full;
      op->reinit_vector(full);
      full.block(0) = system.r_fe;
      full.block(0) *= -1;
      op->set_particle_part(full, -system.r_p);
      free.reinit_vector(rhs);
      free.restrict(full, rhs);
    }
    free.reinit_vector(solution);

    const double rhs_norm = rhs.l2_norm();
    using FGMRES          = SolverFGMRES<BorderedOperator::BlockVector>;
    using GMRES           = SolverGMRES<BorderedOperator::BlockVector>;
    bool         converged = rhs_norm == 0;
    unsigned int steps     = 0;
    double       residual  = 0;
    // The iterations and the residual from which the current preconditioner's rate counts.
    unsigned int rate_start_step     = 0;
    double       rate_start_residual = rhs_norm;
    // The iterations after which a reused preconditioner's cheap form missed (0: it did not).
    unsigned int missed_after = 0;
    // The cheap form; when it misses the tolerance with a preconditioner built for an
    // earlier operator, once more with one built for this operator: a build costs about
    // a cheap solve, the inner solve behind a drifted preconditioner many (doc/scaling.md).
    while (!converged && cheap_iterations > 0 && !cheap_failed)
      {
        SolverControl control(cheap_iterations, tolerance * rhs_norm, false, false);
        // The cheap form is a fixed linear operator, so GMRES preconditioned from the
        // right builds FGMRES's Krylov space and iterates with half its vectors: it keeps
        // the basis and applies the preconditioner once more to the combination at the end
        // of a cycle, where FGMRES keeps each basis vector's preconditioned image.
        // (deal.II's GMRES counts two work vectors beyond the basis.)
        GMRES gmres(control, GMRES::AdditionalData(basis_size + 2, true));
        preconditioner.inner_solve = false;
        try
          {
            gmres.solve(matrix, solution, rhs, preconditioned);
            converged = true;
          }
        catch (const SolverControl::NoConvergence &)
          {
            // GMRES leaves its best iterate in the solution; the next form goes on from it.
            cheap_failed = true;
          }
        preconditioner.inner_solve = true;
        steps += control.last_step();
        residual = control.last_value();
        if (cheap_failed && !fresh)
          {
            missed_after = steps;
            count();
            rebuild();
            inner_before = preconditioner.inner_iterations();
            parts_before = preconditioner.application_times();
            rate_start_step     = steps;
            rate_start_residual = residual;
          }
      }
    if (!converged)
      {
        SolverControl control(max_iterations, tolerance * rhs_norm, false, false);
        FGMRES        fgmres(control, FGMRES::AdditionalData(basis_size));
        try
          {
            fgmres.solve(matrix, solution, rhs, preconditioned);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            stale = true;
            std::ostringstream s;
            s << "the iterative linear solver did not converge in " << steps + e.last_step
              << " iterations (relative residual " << e.last_residual / rhs_norm << ", target "
              << tolerance << ")";
            throw std::runtime_error(s.str());
          }
        steps += control.last_step();
        residual = control.last_value();
      }
    SolveInfo info;
    info.setup            = rebuilt;
    info.iterations       = steps;
    info.residual         = rhs_norm > 0 ? residual / rhs_norm : 0;
    count();
    info.inner_iterations = inner;
    // Collective: counted on every rank before rank 0 prints.
    if (verbose && velocity_nonzeros == numbers::invalid_dof_index)
      velocity_nonzeros = system.velocity_block_nonzeros();
    if (verbose && Utilities::MPI::this_mpi_process(system.r_fe.get_mpi_communicator()) == 0)
      std::cout << "  iterative solver: " << info.iterations << " outer iterations ("
                << info.inner_iterations << " inner), relative residual " << info.residual << " for "
                << tolerance << "; Newton matrix " << system.A.n_nonzero_elements()
                << " non-zeros, " << velocity_nonzeros << " of them in the velocity block"
                << "; Krylov vectors of the " << free.n_free() << " free of "
                << free.n_full() << " unknowns; cut-cell patch " << preconditioner.patch_size()
                << " unknowns, factored in " << preconditioner.patch_memory() / 1e6
                << " MB (largest rank" << (preconditioner.patch_symmetric()      ? ", symmetric" :
                                                   preconditioner.patch_symmetric_part() ? ", symmetric part" :
                                                                                           "")
                << "); pressure Laplacian "
                << (preconditioner.with_inertia() ? "built" : "left out") << " ("
                << (system.blocks.slow_pressure_modes <
                        NewtonSystem::Blocks::max_counted_pressure_modes ?
                      std::to_string(system.blocks.slow_pressure_modes) :
                      "at least " + std::to_string(system.blocks.slow_pressure_modes))
                << " slow pressure modes); "
                << (missed_after > 0 ? "reused preconditioner missed after " +
                                         std::to_string(missed_after) + " iterations, " :
                                       std::string())
                << (rebuilt ? "preconditioner built in " +
                                std::to_string(preconditioner.setup_time()) + " s (patch " +
                                std::to_string(preconditioner.patch_setup_time()) + " s), " :
                              std::string("preconditioner reused, "))
                << "iterations " << iteration_timer.wall_time()
                << " s (preconditioner since built " << preconditioner.apply_time()
                << " s, its patch " << preconditioner.patch_apply_time()
                << " s; this solve: operator products " << op->vmult_time() - products_before
                << " s, velocity V-cycles " << parts.velocity_cycles
                << " s, multiplier V-cycles " << parts.multiplier_cycles
                << " s, particle block " << parts.particle_block
                << " s)" << std::endl;
    // Iterations per decade of residual reduction compare solves to different tolerances;
    // the counts alone do not (a loose first solve of 3 iterations against a later one of 19
    // to a 30 times smaller tolerance, same matrix, same preconditioner).
    const double decades =
      residual > 0 && rate_start_residual > 0 ? std::log10(rate_start_residual / residual) : 0;
    if (decades >= min_rate_decades)
      {
        const double rate = (info.iterations - rate_start_step) / decades;
        if (fresh || reference_rate == 0)
          reference_rate = std::max(reference_rate, rate);
        else if (rate > rebuild_growth * reference_rate)
          drifted = true;
      }

    BorderedOperator::BlockVector full;
    op->reinit_vector(full);
    free.extend(solution, full);
    x.reinit(system.r_fe.locally_owned_elements(), system.r_fe.get_mpi_communicator());
    x = full.block(0);
    y = op->particle_part(full);
    return info;
  }
} // namespace fdparticle
