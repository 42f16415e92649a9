#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_dgp.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <fdparticle/core/parameter_tools.h>
#include <fdparticle/core/simulation.h>

#include <chrono>
#include <deque>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace fdparticle
{
  namespace
  {
    /// A Newton solve that did not converge: the step may be retried with a smaller Δt.
    class NewtonFailure : public std::runtime_error
    {
    public:
      using std::runtime_error::runtime_error;
    };

    std::string sci(const double x)
    {
      std::ostringstream s;
      s << std::setprecision(3) << x;
      return s.str();
    }

    /// Seconds as "42 s", "12 min" or "3.5 h", for the estimate of the time left.
    std::string format_duration(const double seconds)
    {
      std::ostringstream s;
      s << std::fixed;
      if (seconds < 120)
        s << std::setprecision(0) << seconds << " s";
      else if (seconds < 2 * 3600)
        s << std::setprecision(0) << seconds / 60 << " min";
      else
        s << std::setprecision(1) << seconds / 3600 << " h";
      return s.str();
    }

    double wall_clock()
    {
      return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
    }

    void declare_simulation_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Solver");
      {
        prm.declare_entry("Nonlinear tolerance", "1e-10", Patterns::Double(0),
                          "Newton stops when the residual 2-norm is below this value, or below "
                          "this value times the residual at the start of the step.");
        prm.declare_entry("Max nonlinear iterations", "20", Patterns::Integer(1),
                          "Newton iterations allowed per time step.");
        prm.declare_entry("Line search", "true", Patterns::Bool(),
                          "Halve the Newton step until the residual decreases (Navier-Stokes).");
        prm.declare_entry("Reuse Jacobian", "true", Patterns::Bool(),
                          "Within a time step, keep the factored Jacobian while each iteration "
                          "still reduces the residual tenfold (saves factorizations at low "
                          "Reynolds number); false: exact Newton, a new Jacobian every iteration.");
      }
      prm.leave_subsection();
      prm.enter_subsection("Initial conditions");
      {
        prm.declare_entry("Pressure", "zero", Patterns::Selection("zero|hydrostatic"),
                          "Initial pressure: zero, or hydrostatic (rho_f g + f).(x - x_ref), "
                          "x_ref the centre of the cell at the lower corner, where the pressure "
                          "level is fixed. Velocity, multiplier and particles start at rest.");
      }
      prm.leave_subsection();
    }
  } // namespace

  void declare_all_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Dimension", "3", Patterns::Integer(2, 3), "Space dimension, 2 or 3.");
    Domain<3>::declare_parameters(prm);
    Fluid<3>::declare_parameters(prm);
    ParticleSet<3>::declare_parameters(prm);
    TimeStepper::declare_parameters(prm);
    CutCellQuadrature<3>::declare_parameters(prm);
    NavierStokesAssembler<3>::declare_parameters(prm);
    BorderedSystem::declare_parameters(prm);
    OutputWriter<3>::declare_parameters(prm);
    ParticleRefinement<3>::declare_parameters(prm);
    Checkpointer<3>::declare_parameters(prm);
    WallRepulsion<3>::declare_parameters(prm);
    declare_simulation_parameters(prm);
  }

  template <int dim>
  Simulation<dim>::Simulation(ParameterHandler &prm, const MPI_Comm comm)
    : comm(comm)
    , pcout(std::cout, Utilities::MPI::this_mpi_process(comm) == 0)
    , prm(prm)
    , triangulation(comm,
                    typename Triangulation<dim>::MeshSmoothing(
                      Triangulation<dim>::limit_level_difference_at_vertices))
    , fe(FE_Q<dim>(2), dim, FE_Q<dim>(2), dim, FE_DGP<dim>(1), 1)
    , dof_handler(triangulation)
    , assembler(fe, fluid, particles, quadrature)
  {
    domain.parse_parameters(prm);
    fluid.parse_parameters(prm);
    particles.parse_parameters(prm, domain);
    time.parse_parameters(prm);
    quadrature.parse_parameters(prm);
    assembler.parse_parameters(prm);
    system.parse_parameters(prm);
    output.parse_parameters(prm);
    refinement.parse_parameters(prm);
    {
      // Refused here, before the mesh is built: an unaffordable one fails by running out of
      // memory at an unpredictable point, on one rank only, or takes the machine down.
      const double cells = refinement.estimated_cells(domain, particles);
      AssertThrow(cells <= Domain<dim>::max_cells,
                  ExcMessage("The mesh would have about " + ParameterTools::format_count(cells) +
                             " cells (" + ParameterTools::format_count(domain.n_cells()) +
                             " base cells, Refinement/Particle refinement levels = " +
                             std::to_string(refinement.levels()) +
                             " around the particles); fdparticle refuses meshes of more than " +
                             ParameterTools::format_count(Domain<dim>::max_cells) +
                             " cells (0.1-1 TB of memory). Use fewer particle refinement "
                             "levels, a narrower Refinement/Band width or a coarser base mesh."));
      const double h = domain.base_cell_size() / std::pow(2.0, refinement.levels());
      for (unsigned int k = 0; k < particles.size(); ++k)
        AssertThrow(particles[k].radius >= ParticleSet<dim>::min_radius_in_cells * h,
                    ExcMessage("Particle " + std::to_string(k + 1) + " (radius " +
                               ParameterTools::format_count(particles[k].radius) +
                               ") is smaller than " +
                               ParameterTools::format_count(ParticleSet<dim>::min_radius_in_cells) +
                               " times the finest cell edge (h = " +
                               ParameterTools::format_count(h) +
                               "): the mesh cannot resolve it. Refine with Geometry/Global "
                               "refinements or Refinement/Particle refinement levels."));
    }
    checkpointer.parse_parameters(prm, output.directory());
    repulsion.parse_parameters(prm);
    prm.enter_subsection("Solver");
    nonlinear_tolerance = prm.get_double("Nonlinear tolerance");
    max_nonlinear_iterations = prm.get_integer("Max nonlinear iterations");
    line_search = prm.get_bool("Line search");
    reuse_jacobian = prm.get_bool("Reuse Jacobian");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    hydrostatic_start = (prm.get("Pressure") == "hydrostatic");
    prm.leave_subsection();
  }

  template <int dim>
  void Simulation<dim>::setup_dofs()
  {
    TimerOutput::Scope t(*timer, "setup");
    dof_handler.distribute_dofs(fe);
    owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);
    velocity_dofs = DoFTools::extract_dofs(dof_handler, fe.component_mask(FEValuesExtractors::Vector(0)));
    // λ DoFs of owned and ghost cells: the constraints need them on every rank that sees them.
    multiplier_dofs.clear();
    multiplier_dofs.set_size(dof_handler.n_dofs());
    {
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (!cell->is_artificial())
          {
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < dofs.size(); ++i)
              {
                const unsigned int c = fe.system_to_component_index(i).first;
                if (c >= dim && c < 2 * dim)
                  multiplier_dofs.add_index(dofs[i]);
              }
          }
      multiplier_dofs.compress();
    }

    static_constraints.clear();
    static_constraints.reinit(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, static_constraints);
    domain.make_periodicity_constraints(dof_handler, static_constraints);
    static_constraints.close();


    solution.reinit(owned_dofs, comm);
    old_solution.reinit(owned_dofs, comm);
    old_old_solution.reinit(owned_dofs, comm);
    solution_ghost.reinit(owned_dofs, relevant_dofs, comm);
    history_ghost.reinit(owned_dofs, relevant_dofs, comm);

    // The pressure level is fixed by the mean pressure of the cell at the lower corner
    // (the seed's "centre node of the first element"): no wall fixes it.
    const unsigned int p_local = fe.component_to_system_index(2 * dim, 0);
    double             best = std::numeric_limits<double>::max();
    types::global_dof_index best_dof = 0;
    Point<dim>              best_center;
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const double d = cell->center().distance(domain.lower_corner());
          if (d < best)
            {
              best = d;
              cell->get_dof_indices(dofs);
              best_dof = dofs[p_local];
              best_center = cell->center();
            }
        }
    const double       global_best = Utilities::MPI::min(best, comm);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int root = Utilities::MPI::min(
      best == global_best ? Utilities::MPI::this_mpi_process(comm) : n_ranks, comm);
    pressure_reference_dof = Utilities::MPI::broadcast(comm, best_dof, root);
    pressure_reference_point = Utilities::MPI::broadcast(comm, best_center, root);
    assembler.set_pressure_reference(pressure_reference_point);
  }

  template <int dim>
  void Simulation<dim>::adapt_mesh(const bool transfer)
  {
    // One pass refines or coarsens each cell by one level; a particle moves less than a
    // cell per step, so after the initial passes one pass a step keeps up.
    for (unsigned int pass = 0; pass <= refinement.levels(); ++pass)
      {
        if (!refinement.mark(triangulation, particles, base_level))
          return;
        TimerOutput::Scope t(*timer, "refinement");
        triangulation.prepare_coarsening_and_refinement();
        if (!transfer)
          {
            triangulation.execute_coarsening_and_refinement();
            continue;
          }
        std::vector<TrilinosWrappers::MPI::Vector> ghosted(3, solution_ghost);
        ghosted[0] = solution;
        ghosted[1] = old_solution;
        ghosted[2] = old_old_solution;
        parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector> transfer_(
          dof_handler);
        transfer_.prepare_for_coarsening_and_refinement(
          std::vector<const TrilinosWrappers::MPI::Vector *>{&ghosted[0], &ghosted[1], &ghosted[2]});
        triangulation.execute_coarsening_and_refinement();
        setup_dofs();
        std::vector<TrilinosWrappers::MPI::Vector *> out{&solution, &old_solution,
                                                          &old_old_solution};
        transfer_.interpolate(out);
        for (auto *v : out)
          static_constraints.distribute(*v);
      }
  }

  template <int dim>
  void Simulation<dim>::make_constraints()
  {
    TimerOutput::Scope t(*timer, "constraints");
    const FEValuesExtractors::Vector velocities(0);
    const ComponentMask              u_mask = fe.component_mask(velocities);
    const auto support = assembler.particle_support(dof_handler, relevant_dofs);

    for (const bool homogeneous : {true, false})
      {
        AffineConstraints<double> &c = (homogeneous ? update_constraints : state_constraints);
        c.clear();
        c.reinit(relevant_dofs);
        c.merge(static_constraints);
        domain.make_wall_constraints(dof_handler, u_mask, homogeneous, c);
        // λ = 0 where its support meets no particle (seed 3.15a): not part of the solve.
        for (const auto i : multiplier_dofs)
          if (!support.active_multipliers.is_element(i) && !c.is_constrained(i))
            c.add_line(i);
        // Pinning a pressure DoF drops the continuity equation of its cell. That is
        // harmless only while nothing but the walls sees the pressure level: once the
        // interior-pressure penalty acts, it fixes the level itself, and the dropped row
        // would leave a mass source of the size of the penalty in the lower-corner cell,
        // which breaks every mirror symmetry of a scene (doc/method.md §4).
        if (!support.pressure_level_fixed && relevant_dofs.is_element(pressure_reference_dof) &&
            !c.is_constrained(pressure_reference_dof))
          c.add_line(pressure_reference_dof);
        c.close();
      }
  }

  template <int dim>
  void Simulation<dim>::setup_matrix()
  {
    TimerOutput::Scope t(*timer, "setup");
    // The pattern follows the constraints of this step: constrained DoFs (inactive λ,
    // walls) keep only their diagonal, so the direct solver never sees the λ block away
    // from the particles. Couplings of (F1)–(F3), doc/method.md §3: u with everything, λ_i with u_i and λ_i
    // (rigidity, fluid penalty), λ_i with λ_j (strain penalty), p with u; p with p only for the diagonal of the
    // constrained pressure-level DoF (cell-local, so cheap).
    Table<2, DoFTools::Coupling> coupling(2 * dim + 1, 2 * dim + 1);
    for (unsigned int i = 0; i < 2 * dim + 1; ++i)
      for (unsigned int j = 0; j < 2 * dim + 1; ++j)
        {
          const bool u_i = i < dim, u_j = j < dim, p_i = i == 2 * dim, p_j = j == 2 * dim;
          const bool same = (i % dim == j % dim) && !p_i && !p_j;
          // The strain penalty couples the components of λ with each other.
          const bool l_l = !u_i && !u_j && !p_i && !p_j;
          coupling[i][j] = ((u_i && u_j) || (u_i && p_j) || (p_i && u_j) || (p_i && p_j) || same || l_l) ?
                             DoFTools::always :
                             DoFTools::none;
        }
    TrilinosWrappers::SparsityPattern sparsity(owned_dofs, owned_dofs, relevant_dofs, comm);
    DoFTools::make_sparsity_pattern(dof_handler, coupling, sparsity, update_constraints, false,
                                    Utilities::MPI::this_mpi_process(comm));
    sparsity.compress();
    system.reinit(owned_dofs, relevant_dofs, sparsity, comm, particles.n_unknowns());
  }

  template <int dim>
  void Simulation<dim>::set_initial_pressure()
  {
    if (!hydrostatic_start)
      return;
    // Local L2 projection: p is discontinuous, so each cell is independent, and the linear
    // hydrostatic field is reproduced exactly.
    const FEValuesExtractors::Scalar pressure(2 * dim);
    QGauss<dim>                      q(3);
    FEValues<dim> fv(assembler.get_mapping(), fe, q,
                     update_values | update_quadrature_points | update_JxW_values);
    std::vector<unsigned int> p_dofs;
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      if (fe.system_to_component_index(i).first == 2 * dim)
        p_dofs.push_back(i);
    const unsigned int                   np = p_dofs.size();
    FullMatrix<double>                   M(np, np);
    Vector<double>                       b(np), x(np);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    const Tensor<1, dim>                 grad = fluid.hydrostatic_gradient();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          M = 0;
          b = 0;
          for (unsigned int qp = 0; qp < q.size(); ++qp)
            {
              const double ps = grad * (fv.quadrature_point(qp) - pressure_reference_point);
              for (unsigned int i = 0; i < np; ++i)
                {
                  b(i) += ps * fv.shape_value(p_dofs[i], qp) * fv.JxW(qp);
                  for (unsigned int j = 0; j < np; ++j)
                    M(i, j) += fv.shape_value(p_dofs[i], qp) * fv.shape_value(p_dofs[j], qp) *
                               fv.JxW(qp);
                }
            }
          M.gauss_jordan();
          M.vmult(x, b);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < np; ++i)
            solution[dofs[p_dofs[i]]] = x(i);
        }
    solution.compress(VectorOperation::insert);
  }

  template <int dim>
  void Simulation<dim>::update_particle_forces(const std::vector<ParticleIntegrals<dim>> &integrals)
  {
    // doc/method.md §0, §9: F = ρ_f|P|(dV/dt − g) − <λ, e_i>, T = ρ_f J dω/dt − <λ, e_j × r>.
    const auto c = time.coefficients();
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        Particle<dim> &P = particles[k];
        const Tensor<1, dim> dVdt = c[0] * P.velocity + c[1] * P.velocity_old + c[2] * P.velocity_old2;
        const Tensor<1, 3>   dwdt = c[0] * P.omega + c[1] * P.omega_old + c[2] * P.omega_old2;
        P.force = fluid.density * P.volume() * (dVdt - fluid.gravity) - integrals[k].lambda_force;
        P.torque = fluid.density * P.inertia() * dwdt - integrals[k].lambda_torque;
        if (dim == 2)
          P.torque[0] = P.torque[1] = 0;
      }
  }

  template <int dim>
  void Simulation<dim>::solve_time_step(StepStatistics &stats)
  {
    const auto c = time.coefficients();
    // BDF history of the fluid: c1 u^n + c2 u^{n−1}.
    {
      TrilinosWrappers::MPI::Vector h(owned_dofs, comm);
      h.add(c[1], old_solution, c[2], old_old_solution);
      history_ghost = h;
    }
    solution = old_solution;
    state_constraints.distribute(solution);
    solution_ghost = solution;

    auto assemble = [&](const bool with_matrix) {
      TimerOutput::Scope t(*timer, with_matrix ? "assemble system" : "assemble residual");
      last_integrals = assembler.assemble(dof_handler, solution_ghost, history_ghost, c,
                                          update_constraints, with_matrix, system);
      if (repulsion.enabled())
        repulsion.add_to_particle_rows(particles, c, system.r_p,
                                       with_matrix ? &system.D : nullptr);
      return system.residual_norm();
    };

    double residual = assemble(true);
    stats.initial_residual = residual;
    // A non-finite start must not make the target infinite and the step "converged".
    const double target =
      nonlinear_tolerance * std::max(1.0, std::isfinite(residual) ? residual : 1.0);
    unsigned int iteration = 0;
    // Written so that a NaN residual enters the loop (NaN > target is false) and is caught there.
    while (!(residual <= target))
      {
        // Failures the step can be retried from (Simulation::do_time_step).
        if (!std::isfinite(residual))
          throw NewtonFailure("the residual is not finite (" + describe_residual() + ")");
        if (residual > 1e6 * std::max(stats.initial_residual, target))
          throw NewtonFailure("Newton diverges: the residual grew from " +
                              sci(stats.initial_residual) + " to " + sci(residual) + " (" +
                              describe_residual() + ")");
        if (iteration >= max_nonlinear_iterations)
          throw NewtonFailure("Newton did not converge in " +
                              std::to_string(max_nonlinear_iterations) + " iterations (residual " +
                              sci(residual) + " from " + sci(stats.initial_residual) + "; " +
                              describe_residual() + ")");
        TrilinosWrappers::MPI::Vector dx;
        Eigen::VectorXd               dy;
        {
          TimerOutput::Scope t(*timer, "solve");
          try
            {
              system.solve_newton_step(dx, dy);
            }
          catch (const std::exception &e)
            {
              throw NewtonFailure("the linear solve failed: " +
                                  ParameterTools::one_line_message(e));
            }
          update_constraints.distribute(dx);
        }
        ++iteration;
        const TrilinosWrappers::MPI::Vector x0 = solution;
        const Eigen::VectorXd               y0 = particles.get_unknowns();
        double                              theta = 1.0;
        for (;;)
          {
            solution = x0;
            solution.add(theta, dx);
            solution_ghost = solution;
            particles.set_unknowns(y0 + theta * dy);
            if (!fluid.convection)
              break; // linear: the full step is the solution
            const double trial = assemble(false);
            if (!line_search || trial < residual || theta < 1.0 / 16)
              break;
            theta *= 0.5;
          }
        if (!fluid.convection)
          {
            residual = assemble(false);
            if (!std::isfinite(residual))
              throw NewtonFailure("the residual is not finite (" + describe_residual() + ")");
            break; // Stokes: one linear solve per step
          }
        const double previous = residual;
        residual = system.residual_norm();
        // Modified Newton: keep the factored Jacobian while it still cuts the residual
        // tenfold per iteration; a new one costs a new factorization.
        if (residual > target && (!reuse_jacobian || residual > 0.1 * previous))
          residual = assemble(true);
      }
    stats.nonlinear_iterations = iteration;
    stats.residual = residual;
    update_particle_forces(last_integrals);
  }

  template <int dim>
  double Simulation<dim>::max_velocity() const
  {
    double m = 0;
    for (const auto i : velocity_dofs)
      if (owned_dofs.is_element(i))
        m = std::max(m, std::abs(solution[i]));
    return Utilities::MPI::max(m, comm);
  }

  template <int dim>
  void Simulation<dim>::field_statistics(StepStatistics &stats) const
  {
    // One pass over the cells for both field statistics of a step:
    //  - RMS over Ω of p − p_static minus its mean (zero for a fluid at hydrostatic rest);
    //  - (1/|Ω|) ∫_Ω u, the superficial velocity of the periodic-array problems.
    const FEValuesExtractors::Scalar pressure(2 * dim);
    const FEValuesExtractors::Vector velocities(0);
    QGauss<dim>                      q(3);
    FEValues<dim> fv(assembler.get_mapping(), fe, q,
                     update_values | update_quadrature_points | update_JxW_values);
    std::vector<double>         p(q.size());
    std::vector<Tensor<1, dim>> u(q.size());
    // ∫ e, ∫ e², |Ω|, ∫ u_d.
    double               sums[3 + dim] = {};
    const Tensor<1, dim> grad = fluid.hydrostatic_gradient();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          fv[pressure].get_function_values(solution_ghost, p);
          fv[velocities].get_function_values(solution_ghost, u);
          for (unsigned int qp = 0; qp < q.size(); ++qp)
            {
              const double e = p[qp] - grad * (fv.quadrature_point(qp) - pressure_reference_point);
              sums[0] += e * fv.JxW(qp);
              sums[1] += e * e * fv.JxW(qp);
              sums[2] += fv.JxW(qp);
              for (unsigned int d = 0; d < dim; ++d)
                sums[3 + d] += u[qp][d] * fv.JxW(qp);
            }
        }
    Utilities::MPI::sum(ArrayView<const double>(sums, 3 + dim), comm,
                        ArrayView<double>(sums, 3 + dim));
    const double mean = sums[0] / sums[2];
    stats.hydrostatic_deviation = std::sqrt(std::max(0.0, sums[1] / sums[2] - mean * mean));
    stats.mean_velocity = Tensor<1, 3>();
    for (unsigned int d = 0; d < dim; ++d)
      stats.mean_velocity[d] = sums[3 + d] / sums[2];
  }

  template <int dim>
  void Simulation<dim>::write_output(const bool fields)
  {
    TimerOutput::Scope t(*timer, "output");
    output.write_particles_row(time.time(), particles);
    if (fields)
      output.write_fields(time.step_number(), time.time(), assembler.get_mapping(), dof_handler,
                          solution_ghost, assembler.particle_fraction(dof_handler), particles);
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
            where = "particle " + std::to_string(k + 1) + "'s " +
                    (j < dim ? std::string("force balance (") + "xyz"[j] + ")" :
                               std::string(particles.closure() == AngularVelocityClosure::kinematic ?
                                             "angular-velocity closure (" :
                                             "torque balance (") +
                                 "xyz"[RigidBody<dim>::rotation_component(j - dim)] + ")");
          }
      }
    std::ostringstream s;
    s << "largest residual entry " << std::setprecision(3)
      << (largest == std::numeric_limits<double>::max() ? std::string("non-finite") : sci(largest))
      << " in " << where;
    for (unsigned int k = 0; k < particles.size(); ++k)
      if (particles[k].first_unknown != numbers::invalid_unsigned_int)
        s << "; particle " << k + 1 << " V = (" << particles[k].velocity << ")";
    return s.str();
  }

  template <int dim>
  void Simulation<dim>::check_resolution()
  {
    // The ball must span cells for λ to see it; below one cell per radius it is a blur.
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const Particle<dim> &P = particles[k];
        double               h = std::numeric_limits<double>::max();
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned() &&
              cell->center().distance(P.position) < P.radius + cell->diameter())
            h = std::min(h, cell->minimum_vertex_distance());
        h = Utilities::MPI::min(h, comm);
        if (P.radius < h)
          pcout << "Warning: particle " << k + 1 << " (radius " << P.radius
                << ") is smaller than the cells around it (h = " << h << ", d/h = "
                << std::setprecision(3) << 2 * P.radius / h
                << "): it is under-resolved; refine with Geometry/Global refinements or "
                   "Refinement/Particle refinement levels."
                << std::endl;
      }
  }

  template <int dim>
  void Simulation<dim>::start()
  {
    domain.create_mesh(triangulation);
    base_level = triangulation.n_global_levels() - 1;
    if (refinement.enabled())
      adapt_mesh(false);
    setup_dofs();
    make_constraints();
    setup_matrix();
    set_initial_pressure();
    state_constraints.distribute(solution);
    solution_ghost = solution;
    old_solution = solution;
    old_old_solution = solution;
    output.initialize(prm, comm);
    // t = 0: the state before the first step (forces are those of the fluid at rest).
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        particles[k].force = Tensor<1, dim>();
        particles[k].torque = Tensor<1, 3>();
      }
    write_output(output.vtu_due(0));
  }

  template <int dim>
  void Simulation<dim>::resume()
  {
    std::string state;
    try
      {
        state = checkpointer.read_state(comm, particles.size());
      }
    catch (const std::exception &e)
      {
        throw CollectiveError(ParameterTools::one_line_message(e));
      }
    TimerOutput::Scope t(*timer, "checkpoint");
    domain.create_coarse_mesh(triangulation);
    checkpointer.load_mesh(triangulation);
    base_level = domain.n_global_refinements();
    setup_dofs();
    checkpointer.load_vectors(dof_handler, {&solution, &old_solution, &old_old_solution});
    solution_ghost = solution;
    std::istringstream in(state);
    time.load(in);
    particles.load(in);
    smoothness.load(in);
    output.load(in);
    if (in.fail())
      throw CollectiveError("The checkpoint in '" + checkpointer.directory() + "' is incomplete.");
    output.initialize(prm, comm, true, time.step_number(), time.time());
    pcout << "fdparticle: resumed from '" << checkpointer.directory() << "' at step "
          << time.step_number() << ", t = " << time.time() << std::endl;
  }

  template <int dim>
  void Simulation<dim>::write_checkpoint()
  {
    TimerOutput::Scope                         t(*timer, "checkpoint");
    std::vector<TrilinosWrappers::MPI::Vector> ghosted(3, solution_ghost);
    ghosted[0] = solution;
    ghosted[1] = old_solution;
    ghosted[2] = old_old_solution;
    std::ostringstream state;
    time.save(state);
    particles.save(state);
    smoothness.save(state);
    output.save(state);
    checkpointer.write(triangulation, dof_handler, {&ghosted[0], &ghosted[1], &ghosted[2]},
                       particles.size(), state.str());
  }

  template <int dim>
  void Simulation<dim>::do_time_step(StepStatistics &stats)
  {
    const ParticleSet<dim> accepted = particles;
    if (refinement.due(time.step_number()))
      adapt_mesh(true);
    // Give up: keep the last good state (checkpoint, fields) and say why.
    // Back to the state of the last accepted step.
    auto roll_back = [&]() {
      particles = accepted;
      solution = old_solution;
      solution_ghost = solution;
    };
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
        stats.dt = time.next_step();
        particles.prepare_step(time);
        make_constraints();
        setup_matrix();
        std::string failure;
        try
          {
            solve_time_step(stats);
          }
        catch (const NewtonFailure &e)
          {
            failure = e.what();
          }
        const std::string when = "At t = " + std::to_string(time.time() + time.next_step()) +
                                 " (step " + std::to_string(time.step_number() + 1) +
                                 ", dt = " + sci(time.next_step()) + ")";
        if (failure.empty())
          {
            // Positions are checked before the step is accepted. A ball that went through
            // the wall repulsion's range in one step (a fast particle, a long step) is a
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
  void Simulation<dim>::run()
  {
    // Created here, not in the constructor: an input error must not trigger its warnings.
    timer = std::make_unique<TimerOutput>(comm, pcout, TimerOutput::never,
                                                TimerOutput::wall_times);
    try
      {
        run_time_loop();
      }
    catch (...)
      {
        // Released inside the handler: a TimerOutput destroyed during unwinding prints a
        // warning about skipped MPI synchronisation after the one-line error.
        timer.reset();
        throw;
      }
    timer->print_summary();
    timer.reset();
  }

  template <int dim>
  void Simulation<dim>::run_time_loop()
  {
    wall_start = wall_clock();
    checkpointer.check_directory(comm);
    if (checkpointer.resume())
      resume();
    else
      start();
    repulsion.initialize(domain, fluid, particles,
                         domain.base_cell_size() / std::pow(2.0, refinement.levels()));

    pcout << "fdparticle: " << dim << "D, " << triangulation.n_global_active_cells()
          << " cells, " << dof_handler.n_dofs() << " finite-element DoFs + "
          << particles.n_unknowns() << " particle unknowns, " << particles.size()
          << " particle(s), " << time.scheme_name() << ", "
          << (fluid.convection ? "Navier-Stokes" : "Stokes") << ", "
          << Utilities::MPI::n_mpi_processes(comm) << " MPI rank(s)" << std::endl;
    check_resolution();

    // (simulated time, wall seconds) of the recent steps, for the estimate of the time left.
    std::deque<std::pair<double, double>> recent;
    while (!time.finished())
      {
        const double   step_start = wall_clock();
        StepStatistics stats;
        stats.step = time.step_number() + 1;
        do_time_step(stats);
        stats.time_step_reductions = time.reductions();
        smoothness.record(particles);
        time.advance();
        old_old_solution = old_solution;
        old_solution = solution;

        stats.time = time.time();
        stats.cells = triangulation.n_global_active_cells();
        stats.dofs = dof_handler.n_dofs() + particles.n_unknowns();
        stats.max_velocity = max_velocity();
        field_statistics(stats);
        if (refinement.enabled())
          stats.coarse_cut_cells = refinement.coarse_cut_cells(triangulation, particles, base_level);
        write_output(output.vtu_due(time.step_number()));
        if (checkpointer.due(time.step_number()) || (checkpointer.enabled() && time.finished()))
          write_checkpoint();
        stats.wall_seconds = wall_clock() - step_start;
        output.write_statistics_row(stats);
        recent.emplace_back(stats.dt, stats.wall_seconds);
        if (recent.size() > progress_window)
          recent.pop_front();
        print_step_line(stats, recent);
      }
    smoothness.write(output.directory(), pcout, Utilities::MPI::this_mpi_process(comm) == 0);
    pcout << "fdparticle: done in " << std::setprecision(4) << wall_clock() - wall_start
          << " s; output in " << output.directory() << std::endl;
  }

  template <int dim>
  void Simulation<dim>::print_step_line(const StepStatistics &                        stats,
                                        const std::deque<std::pair<double, double>> &recent) const
  {
    double simulated = 0, wall = 0;
    for (const auto &[dt, seconds] : recent)
      {
        simulated += dt;
        wall += seconds;
      }
    const double end = time.end_time();
    const double left = (simulated > 0 ? (end - stats.time) * wall / simulated : 0.0);
    pcout << "step " << std::setw(5) << stats.step << "  t = " << std::setw(10)
          << std::setprecision(6) << stats.time << " / " << end << " (" << std::fixed
          << std::setprecision(0) << std::setw(3) << 100 * stats.time / end << " %)"
          << std::defaultfloat << "  Newton " << stats.nonlinear_iterations << "  residual "
          << std::scientific << std::setprecision(3) << stats.residual << std::defaultfloat
          << "  DoFs " << stats.dofs << "  " << std::setprecision(3) << stats.wall_seconds
          << " s";
    if (!time.finished())
      pcout << "  left ~" << format_duration(left);
    pcout << std::endl;
  }

  template class Simulation<2>;
  template class Simulation<3>;
} // namespace fdparticle
