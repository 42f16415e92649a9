// Simulation: the mesh and its adaptation around the particles, the DoFs, the constraints
// that change with the particles and the layout of the Newton system.

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/velocity_block.h>
#include <fdparticle/fem/velocity_multigrid.h>
#include <fdparticle/fem/block_numbering.h>
#include <fdparticle/fem/introspection.h>

#include <iomanip>
#include <limits>

namespace fdparticle
{
  template <int dim>
  void Simulation<dim>::start()
  {
    domain.create_mesh(triangulation);
    base_level = triangulation.n_global_levels() - 1;
    if (refinement.enabled())
      adapt_mesh(false);
    setup_dofs();
    setup_matrix(make_constraints());
    set_initial_pressure();
    state_constraints.distribute(solution);
    solution_ghost = solution;
    old_solution = solution;
    old_old_solution = solution;
    output.initialize(prm, statistics, comm);
    // t = 0: the state before the first step (forces are those of the fluid at rest).
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        particles[k].force = Tensor<1, dim>();
        particles[k].torque = Tensor<1, 3>();
      }
    write_output(output.vtu_due(0));
  }

  template <int dim>
  void Simulation<dim>::setup_dofs()
  {
    TimerOutput::Scope t(*timer, "setup");
    dof_handler.distribute_dofs(fe);
    pattern_constrained = IndexSet();
    // Chosen once, on the first mesh: 'auto' by its actual unknowns (an estimate from the
    // refinement band before the mesh exists overcounts).
    if (!linear_solver)
      linear_solver = create_linear_solver(prm, dim, dof_handler.n_dofs());
    number_dofs_by_block(dof_handler, linear_solver->assembled_data().cell_pressure_masses,
                         system.blocks);
    if (linear_solver->assembled_data().matrix_free_velocity_block)
      {
        if (!velocity_block)
          velocity_block = std::make_shared<VelocityBlock<dim>>(assembler.get_mapping(), domain);
        velocity_block->reinit(dof_handler, system.blocks, update_constraints);
        system.blocks.velocity_product = velocity_block;
        if (!velocity_multigrid)
          velocity_multigrid = std::make_shared<VelocityMultigrid<dim>>(assembler.get_mapping(),
                                                                        domain, *velocity_block);
        velocity_multigrid->reinit();
        system.blocks.velocity_inverse = velocity_multigrid;
      }
    owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);
    // Owned velocity DoFs; λ DoFs of owned and ghost cells (the constraints need them on
    // every rank that sees them).
    velocity_dofs   = system.blocks.global_dofs(NewtonSystem::Blocks::velocity) & owned_dofs;
    multiplier_dofs = system.blocks.global_dofs(NewtonSystem::Blocks::multiplier) & relevant_dofs;

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
    const unsigned int p_local = fe.component_to_system_index(Introspection<dim>::pressure_component, 0);
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
        change_mesh(transfer);
      }
  }

  template <int dim>
  void Simulation<dim>::change_mesh(const bool transfer)
  {
    TimerOutput::Scope t(*timer, "refinement");
    triangulation.prepare_coarsening_and_refinement();
    if (!transfer)
      {
        triangulation.execute_coarsening_and_refinement();
        return;
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
    std::vector<TrilinosWrappers::MPI::Vector *> out{&solution, &old_solution, &old_old_solution};
    transfer_.interpolate(out);
    for (auto *v : out)
      static_constraints.distribute(*v);
  }

  template <int dim>
  void Simulation<dim>::rebalance()
  {
    // The cut cells move with the particles, and a mesh that is not refined around them
    // is partitioned only once: re-run the weighted partition (a mesh change without
    // flags) when the most loaded rank carries max_partition_imbalance times the mean.
    if (!quadrature.weighted_partition() || Utilities::MPI::n_mpi_processes(comm) == 1)
      return;
    double load = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        load += quadrature.partition_weight(cell, particles);
    const auto loads = Utilities::MPI::min_max_avg(load, comm);
    if (loads.max <= max_partition_imbalance * loads.avg)
      return;
    change_mesh(true);
    pcout << "  partition rebalanced: the most loaded rank had " << std::fixed
          << std::setprecision(2) << loads.max / loads.avg << std::defaultfloat
          << std::setprecision(6) << " times the mean load" << partition_summary() << std::endl;
  }

  template <int dim>
  std::string Simulation<dim>::partition_summary() const
  {
    if (Utilities::MPI::n_mpi_processes(comm) == 1)
      return "";
    // Equal cell counts, or unequal ones where the cut cells weigh more (Quadrature/Cut
    // cell cost).
    const auto cells =
      Utilities::MPI::min_max_avg(double(triangulation.n_locally_owned_active_cells()), comm);
    return " (" + std::to_string(int(cells.min)) + "-" + std::to_string(int(cells.max)) +
           " cells each)";
  }

  template <int dim>
  typename NavierStokesAssembler<dim>::ParticleSupport Simulation<dim>::make_constraints()
  {
    TimerOutput::Scope t(*timer, "constraints");
    const ComponentMask u_mask = fe.component_mask(Introspection<dim>::velocities());
    const auto support = assembler.particle_support(dof_handler, relevant_dofs, static_constraints);
    const auto links = pressure_agglomeration.links(dof_handler);
    current_links.clear();
    for (const auto &link : links)
      {
        current_links.push_back(link.cell_dofs[0]);
        current_links.insert(current_links.end(), link.masters.begin(), link.masters.end());
      }

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
        PressureAgglomeration<dim>::add_to(links, c);
        c.close();
      }
    return support;
  }

  template <int dim>
  void Simulation<dim>::setup_matrix(
    const typename NavierStokesAssembler<dim>::ParticleSupport &support)
  {
    TimerOutput::Scope t(*timer, "setup");
    // The pattern follows the constraints of this step: constrained DoFs (inactive λ,
    // walls) keep only their diagonal, so the direct solver never sees the λ block away
    // from the particles. Couplings of (F1)–(F3), doc/method.md §3: u with everything, λ_i with u_i and λ_i
    // (rigidity, fluid penalty), λ_i with λ_j (strain penalty), p with u; p with p only for the diagonal of the
    // constrained pressure-level DoF (cell-local, so cheap). u with u not where the
    // program applies the velocity block without a matrix (VelocityBlock): then A holds
    // only the constrained velocity rows' diagonal.
    using Field = typename Introspection<dim>::Field;
    constexpr unsigned int       n_components = Introspection<dim>::n_components;
    Table<2, DoFTools::Coupling> coupling(n_components, n_components);
    const bool matrix_free = linear_solver->assembled_data().matrix_free_velocity_block;
    for (unsigned int i = 0; i < n_components; ++i)
      for (unsigned int j = 0; j < n_components; ++j)
        {
          const Field f_i = Introspection<dim>::field(i), f_j = Introspection<dim>::field(j);
          const bool  u_i = f_i == Field::velocity, u_j = f_j == Field::velocity;
          const bool  p_i = f_i == Field::pressure, p_j = f_j == Field::pressure;
          const bool  same = (i % dim == j % dim) && !p_i && !p_j;
          // The strain penalty couples the components of λ with each other.
          const bool l_l = f_i == Field::multiplier && f_j == Field::multiplier;
          coupling[i][j] = (matrix_free && u_i && u_j) ? DoFTools::none :
                           ((u_i && u_j) || (u_i && p_j) || (p_i && u_j) || (p_i && p_j) || same || l_l) ?
                             DoFTools::always :
                             DoFTools::none;
        }
    // The pattern follows from the DoFs and from which of them the constraints fix (each
    // line is one of the mesh's hanging-node or periodicity lines, or a zero line): while
    // both stay, A keeps its pattern and none is built.
    IndexSet constrained(dof_handler.n_dofs());
    for (const auto i : relevant_dofs)
      if (update_constraints.is_constrained(i))
        constrained.add_index(i);
    constrained.compress();
    const bool same_constraints = pattern_constrained.size() == constrained.size() &&
                                  pattern_constrained == constrained &&
                                  pattern_links == current_links;
    const bool keep = Utilities::MPI::min(same_constraints ? 1 : 0, comm) == 1;
    TrilinosWrappers::SparsityPattern sparsity;
    if (!keep)
      {
        sparsity.reinit(owned_dofs, owned_dofs, relevant_dofs, comm);
        DoFTools::make_sparsity_pattern(dof_handler, coupling, sparsity, update_constraints,
                                        false, Utilities::MPI::this_mpi_process(comm));
        sparsity.compress();
      }
    pattern_constrained = std::move(constrained);
    pattern_links       = current_links;
    // A pattern equal to the one A has keeps A and whatever the linear solver built on it
    // (a direct solver's symbolic factorization): steps in which no DoF changes its
    // constraint status pay only for the new values.
    const bool new_pattern = !keep && !system.has_pattern(sparsity);
    if (new_pattern)
      linear_solver->pattern_changed();
    system.reinit(owned_dofs, relevant_dofs, sparsity, new_pattern,
                  assembler.border_pattern(support, update_constraints, owned_dofs,
                                           relevant_dofs, comm),
                  comm);
    std::vector<unsigned int> &free = system.blocks.free_dofs;
    free.clear();
    for (unsigned int i = 0; i < owned_dofs.n_elements(); ++i)
      if (!update_constraints.is_constrained(owned_dofs.nth_index_in_set(i)))
        free.push_back(i);
    linear_solver->operator_changed();
  }

  template <int dim>
  void Simulation<dim>::set_initial_pressure()
  {
    if (!hydrostatic_start)
      return;
    // Local L2 projection: p is discontinuous, so each cell is independent, and the linear
    // hydrostatic field is reproduced exactly.
    const QGauss<dim> q = Introspection<dim>::cell_quadrature();
    FEValues<dim> fv(assembler.get_mapping(), fe, q,
                     update_values | update_quadrature_points | update_JxW_values);
    std::vector<unsigned int> p_dofs;
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      if (fe.system_to_component_index(i).first == Introspection<dim>::pressure_component)
        p_dofs.push_back(i);
    const unsigned int                   np = p_dofs.size();
    FullMatrix<double>                   M(np, np);
    Vector<double>                       b(np), x(np);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fv.reinit(cell);
          M = 0;
          b = 0;
          for (unsigned int qp = 0; qp < q.size(); ++qp)
            {
              const double ps =
                fluid.hydrostatic_pressure(fv.quadrature_point(qp), pressure_reference_point);
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

  // The members defined in this file, for both dimensions (an explicit instantiation of a
  // class instantiates the members defined where it stands).
  template class Simulation<2>;
  template class Simulation<3>;
} // namespace fdparticle
