// Simulation: one time step. Newton's method on the step's system (through NewtonSolver),
// the retry with a halved step when it fails (doc/method.md §5), and the particle forces.

#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/velocity_block.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace fdparticle
{
  template <int dim>
  void Simulation<dim>::do_time_step()
  {
    const ParticleSet<dim> accepted = particles;
    if (refinement.due(time.step_number()))
      adapt_mesh(true);
    rebalance();
    // Back to the state of the last accepted step.
    auto roll_back = [&]() {
      particles = accepted;
      solution = old_solution;
      solution_ghost = solution;
    };
    // Give up: keep the last good state (checkpoint, fields) and say why.
    auto stop = [&](const std::string &why) {
      roll_back();
      write_checkpoint();
      if (!output.vtu_due(time.step_number()))
        write_output(true);
      throw CollectiveError(
        why + " The state at t = " + std::to_string(time.time()) + " (step " +
        std::to_string(time.step_number()) + ") is in the checkpoint '" +
        checkpointer.directory() + "' (resume with Checkpointing/Resume = true).");
    };
    for (;;)
      {
        statistics.set("dt", time.next_step());
        particles.prepare_step(time);
        setup_matrix(make_constraints());
        // A failed Newton solve is retried with a smaller step, like a position check below.
        const NewtonSolver::Result result  = solve_time_step();
        std::string                failure = result.message;
        const std::string when = "At t = " + std::to_string(time.time() + time.next_step()) +
                                 " (step " + std::to_string(time.step_number() + 1) +
                                 ", dt = " + ParameterTools::format_short(time.next_step()) + ")";
        // Memory that a linear solve cannot get is not found in a shorter step.
        if (result.outcome == NewtonSolver::Outcome::out_of_memory)
          stop(when + ": " + failure);
        if (failure.empty())
          {
            // Positions are checked before the step is accepted. A ball that went through
            // the wall repulsion's or the collision range in one step (a fast particle, a long step) is a
            // failed step like a Newton failure: with a shorter step the implicit repulsion
            // acts in time. Only when Δt cannot be halved further does the run stop.
            particles.finish_step(time);
            try
              {
                particles.check_positions(domain, time.time() + time.next_step());
                return;
              }
            catch (const std::exception &e)
              {
                failure = ParameterTools::one_line_message(e);
                if (!failure.empty() && failure.back() == '.')
                  failure.pop_back();
              }
          }
        roll_back();
        if (!time.reduce_step())
          stop(when + ": " + failure +
               "; the time step cannot be halved further (Time/Max time step reductions).");
        pcout << "  " << when << ": " << failure << "; retrying with dt = " << time.next_step()
              << std::endl;
      }
  }

  template <int dim>
  NewtonSolver::Result Simulation<dim>::solve_time_step()
  {
    const auto c = time.coefficients();
    system.blocks.mass_coefficient = fluid.density * c[0];
    system.blocks.viscosity        = fluid.viscosity;
    system.blocks.slow_pressure_modes =
      domain.count_modes_below(system.blocks.inertial_wavenumber(),
                               NewtonSystem::Blocks::max_counted_pressure_modes);
    system.blocks.base_cell_size = domain.base_cell_size();
    // BDF history of the fluid: c1 u^n + c2 u^{n−1}.
    {
      TrilinosWrappers::MPI::Vector h(owned_dofs, comm);
      h.add(c[1], old_solution, c[2], old_old_solution);
      history_ghost = h;
    }
    // Newton's initial guess (doc/method.md §5): u^n, or u^n + w (u^n − u^{n−1}) where its
    // residual is smaller.
    const Eigen::VectorXd last_step_velocities = particles.get_unknowns();
    auto start_from = [&](const bool extrapolated) {
      solution = old_solution;
      if (extrapolated)
        {
          const double w = time.extrapolation_weight();
          solution.sadd(1.0 + w, -w, old_old_solution);
          particles.extrapolate_velocities(time);
        }
      else
        particles.set_unknowns(last_step_velocities);
      state_constraints.distribute(solution);
      solution_ghost = solution;
    };
    start_from(false);

    // The state before the last correction and the correction (dx, dy).
    TrilinosWrappers::MPI::Vector x0, dx;
    Eigen::VectorXd               y0, dy;
    NewtonSolver::Problem         problem;
    unsigned int                  jacobians = 0;
    problem.linear   = !fluid.convection;
    problem.assemble = [&](const bool with_jacobian) {
      TimerOutput::Scope t(*timer, with_jacobian ? "assemble system" : "assemble residual");
      std::vector<FullMatrix<double>> cut_matrices;
      const bool matrix_free = with_jacobian && velocity_block;
      last_integrals = assembler.assemble(dof_handler, solution_ghost, history_ghost, c,
                                          update_constraints, with_jacobian, system,
                                          matrix_free ? &cut_matrices : nullptr);
      if (matrix_free)
        velocity_block->set_jacobian(fluid.density, fluid.viscosity, c[0],
                                     fluid.convection ? &solution : nullptr,
                                     std::move(cut_matrices));
      interactions.add_to_particle_rows(particles, c, system.r_p,
                                        with_jacobian ? &system.D : nullptr);
      if (with_jacobian)
        {
          linear_solver->operator_changed();
          ++jacobians;
        }
      return system.residual_norm();
    };
    unsigned int inner_iterations = 0, solver_setups = 0;
    problem.solve = [&](const double relative_tolerance) {
      LinearSolver::SolveInfo info;
      {
        TimerOutput::Scope t(*timer, "solve");
        info = linear_solver->solve(system, relative_tolerance, dx, dy);
        update_constraints.distribute(dx);
      }
      inner_iterations += info.inner_iterations;
      solver_setups += info.setup;
      x0 = solution;
      y0 = particles.get_unknowns();
      return info.iterations;
    };
    problem.apply_update = [&](const double theta) {
      solution = x0;
      solution.add(theta, dx);
      solution_ghost = solution;
      particles.set_unknowns(y0 + theta * dy);
    };
    problem.describe_residual = [&]() { return describe_residual(); };
    // Two residual evaluations decide, not the Jacobian's assembly: after a start from
    // rest or in a flow that only jitters as the particles cross cells, u^n often wins.
    bool extrapolated = false;
    if (newton.extrapolate && time.extrapolation_weight() != 0.0)
      {
        const double last_step_residual = problem.assemble(false);
        start_from(true);
        extrapolated = problem.assemble(false) < last_step_residual; // a NaN loses
        if (!extrapolated)
          start_from(false);
      }

    const NewtonSolver::Result result = newton.solve(problem);
    statistics.set("initial_residual", result.initial_residual);
    statistics.set("extrapolated_start", extrapolated ? 1 : 0);
    if (result.converged())
      {
        statistics.set("nonlinear_iterations", result.iterations);
        statistics.set("linear_iterations", result.linear_iterations);
        statistics.set("inner_iterations", inner_iterations);
        statistics.set("jacobians", jacobians);
        statistics.set("solver_setups", solver_setups);
        statistics.set("residual", result.residual);
        update_particle_forces(last_integrals);
      }
    return result;
  }

  template <int dim>
  void Simulation<dim>::update_particle_forces(const std::vector<ParticleIntegrals<dim>> &integrals)
  {
    // doc/method.md §0, §9: F = ρ_f|P|(dV/dt − g) − <λ, e_i>, T = ρ_f d(Jω)/dt − <λ, e_j × r>.
    const auto c = time.coefficients();
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        Particle<dim> &P = particles[k];
        P.force = fluid.density * P.volume() * (P.acceleration(c) - fluid.gravity) -
                  integrals[k].lambda_force;
        P.torque = P.angular_momentum_rate(c, fluid.density) - integrals[k].lambda_torque;
        if (dim == 2)
          P.torque[0] = P.torque[1] = 0;
      }
  }

  template <int dim>
  std::string Simulation<dim>::describe_residual() const
  {
    // The largest entry of each block of the residual; non-finite entries win.
    auto bigger = [](const double a, const double b) {
      return !std::isfinite(a) || (std::isfinite(b) && a > b);
    };
    double       fe_max[3] = {0, 0, 0}; // momentum, rigidity (λ rows), continuity
    for (const auto i : system.r_fe.locally_owned_elements())
      {
        const double       v = std::abs(system.r_fe[i]);
        const unsigned int block =
          velocity_dofs.is_element(i) ? 0 : (multiplier_dofs.is_element(i) ? 1 : 2);
        if (bigger(v, fe_max[block]))
          fe_max[block] = v;
      }
    for (double &m : fe_max)
      m = Utilities::MPI::max(std::isfinite(m) ? m : std::numeric_limits<double>::max(), comm);
    const char *fe_names[3] = {"the fluid momentum equation", "the rigidity constraint (lambda rows)",
                               "the continuity equation"};
    unsigned int which = 0;
    for (unsigned int b = 1; b < 3; ++b)
      if (fe_max[b] > fe_max[which])
        which = b;
    std::string where = fe_names[which];
    double      largest = fe_max[which];
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const Particle<dim> &P = particles[k];
        if (P.first_unknown == numbers::invalid_unsigned_int)
          continue;
        for (unsigned int j = 0; j < RigidBody<dim>::n_unknowns; ++j)
          {
            const double v = std::abs(system.r_p[P.first_unknown + j]);
            if (!bigger(v, largest))
              continue;
            largest = std::isfinite(v) ? v : std::numeric_limits<double>::max();
            where = "particle " + std::to_string(k) + "'s " +
                    (j < dim ? std::string("force balance (") + "xyz"[j] + ")" :
                               std::string(particles.closure() == AngularVelocityClosure::kinematic ?
                                             "angular-velocity closure (" :
                                             "torque balance (") +
                                 "xyz"[RigidBody<dim>::rotation_component(j - dim)] + ")");
          }
      }
    std::ostringstream s;
    s << "largest residual entry " << std::setprecision(3)
      << (largest == std::numeric_limits<double>::max() ? std::string("non-finite") : ParameterTools::format_short(largest))
      << " in " << where;
    for (unsigned int k = 0; k < particles.size(); ++k)
      if (particles[k].first_unknown != numbers::invalid_unsigned_int)
        s << "; particle " << k << " V = (" << particles[k].velocity << ")";
    return s.str();
  }

  // The members defined in this file, for both dimensions (an explicit instantiation of a
  // class instantiates the members defined where it stands).
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace fdparticle
