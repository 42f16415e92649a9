#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <fdparticle/fem/introspection.h>
#include <fdparticle/fem/navier_stokes_assembler.h>
#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/rigid_body.h>

#include <algorithm>
#include <map>
#include <numeric>

namespace fdparticle
{
  namespace
  {
    /// FEValues for the rule of a cell: the two fixed rules are reused, a rule made for
    /// this cell alone (level set) gets its own object.
    template <int dim>
    FEValues<dim> &fe_values_for(const typename CutCellQuadrature<dim>::CellRule &rule,
                                 FEValues<dim> &regular, FEValues<dim> &cut,
                                 std::unique_ptr<FEValues<dim>> &cell_specific)
    {
      if (rule.quadrature == &rule.cell_specific)
        {
          cell_specific = std::make_unique<FEValues<dim>>(regular.get_mapping(), regular.get_fe(),
                                                          rule.cell_specific,
                                                          regular.get_update_flags());
          return *cell_specific;
        }
      return rule.kind == CellKind::cut ? cut : regular;
    }

    /// The unknowns of a free particle: its columns of B and Cᵀ.
    template <int dim>
    std::vector<types::global_dof_index> unknowns_of(const Particle<dim> &particle)
    {
      std::vector<types::global_dof_index> unknowns(RigidBody<dim>::n_unknowns);
      std::iota(unknowns.begin(), unknowns.end(), particle.first_unknown);
      return unknowns;
    }
  } // namespace

  template <int dim>
  void NavierStokesAssembler<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    prm.declare_entry("Pairing time step", "0", Patterns::Anything(),
                      "dt_p >= 0. 0: the pairing <lambda, v> = int(alpha lambda.v + mu grad "
                      "lambda : grad v) uses alpha = 3 rho/(2 dt) of the current step (the seed). "
                      "dt_p > 0: alpha = 3 rho/(2 dt_p) whatever dt is, so the discrete "
                      "constraint does not change with dt; set it for time-step studies "
                      "(doc/method.md §4).");
    prm.declare_entry("Pairing viscous weight", "10", Patterns::Anything(),
                      "c >= 0: the pairing over ball k weighs lambda.v with kappa = alpha + c "
                      "mu/R_k^2 instead of alpha (constraint, force and torque, fluid penalty), "
                      "which keeps the force mode of lambda bounded in slow steps, so two balls "
                      "whose cut cells touch keep their own motions. 0: the seed's alpha alone "
                      "(doc/method.md §4).");
    prm.leave_subsection();
    CutCellPenalties<dim>::declare_parameters(prm);
    InteriorPressure<dim>::declare_parameters(prm);
  }

  template <int dim>
  void NavierStokesAssembler<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    pairing_time_step =
      ParameterTools::get_non_negative(prm, "Pairing time step", "Multiplier/Pairing time step");
    pairing_viscous_weight = ParameterTools::get_non_negative(prm, "Pairing viscous weight",
                                                              "Multiplier/Pairing viscous weight");
    prm.leave_subsection();
    cut_cell_penalties.parse_parameters(prm);
    interior_pressure.parse_parameters(prm);
  }

  template <int dim>
  NavierStokesAssembler<dim>::NavierStokesAssembler(const FESystem<dim> &         fe,
                                                    const Fluid<dim> &            fluid,
                                                    const ParticleSet<dim> &      particles,
                                                    const CutCellQuadrature<dim> &quadrature)
    : fe(fe)
    , fluid(fluid)
    , particles(particles)
    , quadrature(quadrature)
    , fluid_momentum(fluid)
    , interior_pressure(fluid)
    , multiplier_pairing(fluid, particles)
    , cut_cell_penalties(fluid, particles)
    , particle_equations(fluid, particles)
    , terms{&fluid_momentum, &interior_pressure, &multiplier_pairing, &cut_cell_penalties}
  {}

  template <int dim>
  std::vector<ParticleIntegrals<dim>> NavierStokesAssembler<dim>::assemble(
    const DoFHandler<dim> &dof_handler, const TrilinosWrappers::MPI::Vector &solution,
    const TrilinosWrappers::MPI::Vector &history, const std::array<double, 3> &c,
    const AffineConstraints<double> &constraints, const bool with_matrix,
    NewtonSystem &system, std::vector<FullMatrix<double>> *cut_velocity_matrices) const
  {
    using RB = RigidBody<dim>;
    // The FEValues of the scalar elements: the FE_Q that u and λ share, and the pressure's
    // (AssemblyScratch::reinit), for each kind of rule.
    const auto base_of = [&](const unsigned int component) -> const FiniteElement<dim> & {
      return fe.base_element(fe.component_to_base_index(component).first);
    };
    const FiniteElement<dim> &scalar_fe = base_of(Introspection<dim>::first_velocity_component);
    const FiniteElement<dim> &pressure_fe = base_of(Introspection<dim>::pressure_component);
    Assert(base_of(Introspection<dim>::first_multiplier_component).get_name() == scalar_fe.get_name(),
           ExcMessage("u and λ must have the same scalar element."));
    const UpdateFlags flags =
      update_values | update_gradients | update_quadrature_points | update_JxW_values;
    FEValues<dim> fe_regular(mapping, scalar_fe, quadrature.regular_rule(), flags);
    FEValues<dim> fe_cut(mapping, scalar_fe, quadrature.cut_rule(), flags);
    const UpdateFlags pressure_flags = update_values | update_gradients;
    FEValues<dim> pressure_regular(mapping, pressure_fe, quadrature.regular_rule(), pressure_flags);
    FEValues<dim> pressure_cut(mapping, pressure_fe, quadrature.cut_rule(), pressure_flags);
    std::unique_ptr<FEValues<dim>> fe_cell_specific, pressure_cell_specific;
    Vector<double> local_solution(fe.n_dofs_per_cell()), local_history(fe.n_dofs_per_cell());

    // α of the pairing <λ, v> (doc/method.md §0), to which each ball adds c μ/R²
    // (AssemblyScratch::pairing_weight); the fluid's own ρ c0 u stays in the momentum rows.
    const double alpha =
      (pairing_time_step > 0 ? 1.5 * fluid.density / pairing_time_step : fluid.density * c[0]);
    const unsigned int        n = fe.n_dofs_per_cell();
    AssemblyScratch<dim>      s(fe, c, alpha, pairing_viscous_weight * fluid.viscosity, with_matrix);
    AssemblyCopy<dim>         copy(n, particles.size());
    std::vector<types::global_dof_index> dof_indices(n);
    typename CutCellQuadrature<dim>::CellRule rule;
    // The particle unknowns, the columns of B and Cᵀ, are not DoFs: nothing constrains them.
    const AffineConstraints<double> no_constraints;

    system.zero(with_matrix);
    // The pressure mass over each cell and its fluid part, for the iterative solver's
    // pressure Schur complement (NewtonSystem::Blocks, doc/method.md §8).
    NewtonSystem::Blocks &blocks         = system.blocks;
    const unsigned int    n_p            = blocks.pressure_dofs_per_cell;
    const bool            fluid_mass     = with_matrix && n_p > 0;
    types::global_dof_index   first_pressure = 0; // this rank's first pressure DoF
    if (fluid_mass)
      {
        const auto &range = blocks.range[Utilities::MPI::this_mpi_process(
          dof_handler.get_communicator())];
        first_pressure = range[NewtonSystem::Blocks::pressure];
        const types::global_dof_index n_pressure =
          range[NewtonSystem::Blocks::pressure + 1] - first_pressure;
        blocks.pressure_fluid_mass.assign(n_pressure * n_p, 0.0);
        blocks.pressure_mass.assign(n_pressure * n_p, 0.0);
        blocks.cell_particle.assign(n_pressure / n_p, -1);
        blocks.cell_fluid_fraction.assign(n_pressure / n_p, 1.0);
        blocks.velocity_mass = TrilinosWrappers::MPI::Vector(system.r_fe); // zero here
      }
    Vector<double> local_velocity_mass(n);
    const unsigned int n_velocity = scalar_fe.n_dofs_per_cell();
    std::vector<unsigned int> velocity_dofs; // the cell's, in the system element
    for (unsigned int i = 0; i < n; ++i)
      if (Introspection<dim>::field(fe.system_to_component_index(i).first) ==
          Introspection<dim>::Field::velocity)
        velocity_dofs.push_back(i);
    if (cut_velocity_matrices)
      cut_velocity_matrices->assign(dof_handler.get_triangulation().n_active_cells(),
                                    FullMatrix<double>());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        quadrature.reinit(cell, particles, rule);
        FEValues<dim> &fv = fe_values_for<dim>(rule, fe_regular, fe_cut, fe_cell_specific);
        FEValues<dim> &fv_p =
          fe_values_for<dim>(rule, pressure_regular, pressure_cut, pressure_cell_specific);
        // As cells of the mesh: the scalar elements are not the DoFHandler's.
        const typename Triangulation<dim>::cell_iterator mesh_cell(cell);
        fv.reinit(mesh_cell);
        fv_p.reinit(mesh_cell);
        quadrature.assign_owners(fv.get_quadrature_points(), particles, rule);

        // The cell: its kind, its shape functions and the iterate at its points.
        const unsigned int nq = fv.n_quadrature_points;
        s.kind = rule.kind;
        s.has_particle = rule.has_particle_point();
        const double theta  = rule.particle_fraction(fv.get_JxW_values());
        s.particle_fraction = (rule.kind == CellKind::cut ? theta : 0.0);
        cell->get_dof_values(solution, local_solution);
        cell->get_dof_values(history, local_history);
        s.reinit(fv, fv_p, local_solution, local_history);

        // What the cell adds to: the border vectors of the free particles it meets.
        copy.rhs = 0;
        if (with_matrix)
          copy.matrix = 0;
        copy.touching.clear();
        for (const int k : rule.owner)
          if (k >= 0 && std::find(copy.touching.begin(), copy.touching.end(), k) == copy.touching.end())
            {
              copy.touching.push_back(k);
              if (with_matrix && particles[k].first_unknown != numbers::invalid_unsigned_int)
                {
                  copy.border_B[k].reinit(n, RB::n_unknowns);
                  copy.border_C[k].reinit(n, RB::n_unknowns);
                }
            }

        s.weights.resize(nq);
        s.owners = rule.owner;
        s.nearest_surfaces.resize(nq);
        for (unsigned int q = 0; q < nq; ++q)
          {
            s.q = q;
            s.JxW = s.weights[q] = fv.JxW(q);
            s.x = fv.quadrature_point(q);
            s.particle = rule.owner[q];
            // Near a contact two balls cut the cell: each fluid point takes its nearer one.
            s.cut_particle = s.nearest_surfaces[q] =
              (rule.kind == CellKind::cut && s.particle < 0 && rule.balls.size() > 1) ?
                int(quadrature.nearest_surface(rule, particles, s.x)) :
                rule.particle;
            s.reinit_point(q);
            for (const AssemblyTerm<dim> *term : terms)
              term->assemble_point(s, copy);
          }
        if (with_matrix)
          {
            for (const AssemblyTerm<dim> *term : terms)
              term->assemble_cell_matrix(s, copy);
          }

        if (with_matrix && cut_velocity_matrices && rule.kind == CellKind::cut)
          {
            FullMatrix<double> &m = (*cut_velocity_matrices)[cell->active_cell_index()];
            m.reinit(dim * n_velocity, dim * n_velocity);
            const auto row = [&](const unsigned int c, const unsigned int a) {
              return fe.component_to_system_index(Introspection<dim>::first_velocity_component + c, a);
            };
            for (unsigned int ci = 0; ci < dim; ++ci)
              for (unsigned int a = 0; a < n_velocity; ++a)
                for (unsigned int cj = 0; cj < dim; ++cj)
                  for (unsigned int b = 0; b < n_velocity; ++b)
                    m(ci * n_velocity + a, cj * n_velocity + b) = copy.matrix(row(ci, a), row(cj, b));
          }
        // The caller applies the velocity block without a matrix (VelocityBlock); A's
        // pattern leaves it out, and zeros are not written.
        if (with_matrix && cut_velocity_matrices)
          for (const unsigned int i : velocity_dofs)
            for (const unsigned int j : velocity_dofs)
              copy.matrix(i, j) = 0;
        cell->get_dof_indices(dof_indices);
        if (fluid_mass)
          {
            const auto first = dof_indices[s.pressure_dofs[0]] - first_pressure;
            Assert(first % n_p == 0, ExcInternalError());
            double *fluid_part = &blocks.pressure_fluid_mass[first * n_p];
            double *whole      = &blocks.pressure_mass[first * n_p];
            for (unsigned int q = 0; q < nq; ++q)
              for (unsigned int a = 0; a < n_p; ++a)
                {
                  Assert(dof_indices[s.pressure_dofs[a]] == dof_indices[s.pressure_dofs[0]] + a,
                         ExcInternalError());
                  for (unsigned int b = 0; b < n_p; ++b)
                    {
                      const double m = s.pressure_values[q * n_p + a] *
                                       s.pressure_values[q * n_p + b] * s.weights[q];
                      whole[a * n_p + b] += m;
                      if (rule.owner[q] < 0)
                        fluid_part[a * n_p + b] += m;
                    }
                }
            blocks.cell_fluid_fraction[first / n_p] = 1 - theta;
            // The particle with the most quadrature points in the cell (the lowest index
            // of a tie), or none.
            if (s.has_particle)
              {
                std::map<int, unsigned int> points_of;
                for (const int k : rule.owner)
                  if (k >= 0)
                    ++points_of[k];
                int &covering = blocks.cell_particle[first / n_p];
                for (const auto &[k, count] : points_of)
                  if (covering < 0 || count > points_of[covering])
                    covering = k;
              }
            // The diagonal of the velocity mass matrix: Σ_q φ_s² JxW, the same for every
            // component.
            const CellShapes<dim> &V = s.velocity_shapes;
            local_velocity_mass = 0;
            for (unsigned int f = 0; f < V.n_functions(); ++f)
              {
                double m = 0;
                for (unsigned int q = 0; q < nq; ++q)
                  m += V.row(q)[V.column(0, f)] * V.row(q)[V.column(0, f)] * s.weights[q];
                for (unsigned int comp = 0; comp < dim; ++comp)
                  local_velocity_mass[V.dof(comp, f)] = m;
              }
            constraints.distribute_local_to_global(local_velocity_mass, dof_indices,
                                                   blocks.velocity_mass);
          }
        if (with_matrix)
          {
            constraints.distribute_local_to_global(copy.matrix, copy.rhs, dof_indices, system.A,
                                                   system.r_fe);
            for (const int k : copy.touching)
              if (particles[k].first_unknown != numbers::invalid_unsigned_int)
                {
                  const auto columns = unknowns_of(particles[k]);
                  constraints.distribute_local_to_global(copy.border_B[k], dof_indices,
                                                         no_constraints, columns, system.B);
                  constraints.distribute_local_to_global(copy.border_C[k], dof_indices,
                                                         no_constraints, columns,
                                                         system.C_transposed);
                }
          }
        else
          constraints.distribute_local_to_global(copy.rhs, dof_indices, system.r_fe);
      }

    system.r_fe.compress(VectorOperation::add);
    if (fluid_mass)
      blocks.velocity_mass.compress(VectorOperation::add);
    if (with_matrix)
      {
        system.A.compress(VectorOperation::add);
        if (system.n_particle_unknowns() > 0)
          system.compress_border(VectorOperation::add);
      }

    ParticleIntegrals<dim>::sum_over_ranks(copy.integrals, dof_handler.get_communicator());
    particle_equations.assemble(copy.integrals, c, with_matrix, system);
    return copy.integrals;
  }

  template <int dim>
  typename NavierStokesAssembler<dim>::ParticleSupport
  NavierStokesAssembler<dim>::particle_support(const DoFHandler<dim> &         dof_handler,
                                               const IndexSet &                 locally_relevant,
                                               const AffineConstraints<double> &mesh_constraints) const
  {
    ParticleSupport support;
    bool            any_inside = false;
    // The λ DoFs of the cells a particle meets, and the masters of those among them that
    // hanging nodes or periodicity tie to other DoFs: λ lives in the conforming space, whose
    // basis function of a master includes its slaves' pieces, so the master's support meets
    // the particle too. Without the masters, a constrained λ on a cut cell would be tied to
    // a λ = 0 of the fluid (and which of two periodic DoFs is the master depends on the
    // partition, so the results would depend on the number of ranks).
    std::vector<types::global_dof_index> marked;
    FEValues<dim> fe_regular(mapping, fe, quadrature.regular_rule(), update_quadrature_points);
    FEValues<dim> fe_cut(mapping, fe, quadrature.cut_rule(), update_quadrature_points);
    std::unique_ptr<FEValues<dim>>            fe_cell_specific;
    typename CutCellQuadrature<dim>::CellRule rule;
    std::vector<types::global_dof_index>      dof_indices(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        quadrature.reinit(cell, particles, rule);
        if (rule.kind == CellKind::fluid)
          continue;
        any_inside = any_inside || (rule.kind == CellKind::inside);
        if (rule.kind == CellKind::cut)
          {
            FEValues<dim> &fv = fe_values_for<dim>(rule, fe_regular, fe_cut, fe_cell_specific);
            fv.reinit(cell);
            quadrature.assign_owners(fv.get_quadrature_points(), particles, rule);
            if (!rule.has_particle_point())
              continue;
          }
        std::vector<int> owners(rule.owner);
        std::sort(owners.begin(), owners.end());
        owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
        for (const int k : owners)
          if (k >= 0 && particles[k].first_unknown != numbers::invalid_unsigned_int)
            support.free_particle_cells.emplace_back(cell, k);
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < dof_indices.size(); ++i)
          {
            if (Introspection<dim>::field(fe.system_to_component_index(i).first) !=
                Introspection<dim>::Field::multiplier)
              continue;
            marked.push_back(dof_indices[i]);
            if (const auto *line = mesh_constraints.get_constraint_entries(dof_indices[i]))
              for (const auto &entry : *line)
                marked.push_back(entry.first);
          }
      }
    // Masters may lie outside the locally relevant DoFs: they are ghosts of the marker.
    std::sort(marked.begin(), marked.end());
    marked.erase(std::unique(marked.begin(), marked.end()), marked.end());
    IndexSet ghosts = locally_relevant;
    ghosts.add_indices(marked.begin(), marked.end());
    // Trilinos vectors: the owned DoFs are not one contiguous range (numbered by blocks).
    const MPI_Comm                comm = dof_handler.get_communicator();
    TrilinosWrappers::MPI::Vector marks;
    marks.reinit(dof_handler.locally_owned_dofs(), ghosts, comm, /*vector_writable=*/true);
    // Added, not set: compress must be the same operation on every rank, also on one
    // that marked nothing.
    marks.add(marked, std::vector<double>(marked.size(), 1.0));
    marks.compress(VectorOperation::add);
    TrilinosWrappers::MPI::Vector marker(dof_handler.locally_owned_dofs(), ghosts, comm);
    marker = marks;
    support.active_multipliers.set_size(dof_handler.n_dofs());
    for (const auto i : locally_relevant)
      if (marker[i] > 0)
        support.active_multipliers.add_index(i);
    support.active_multipliers.compress();
    support.pressure_level_fixed =
      interior_pressure.enabled() &&
      Utilities::MPI::logical_or(any_inside, dof_handler.get_communicator());
    return support;
  }

  template <int dim>
  TrilinosWrappers::SparsityPattern
  NavierStokesAssembler<dim>::border_pattern(const ParticleSupport &          support,
                                             const AffineConstraints<double> &constraints,
                                             const IndexSet &                 locally_owned,
                                             const IndexSet &                 locally_relevant,
                                             const MPI_Comm                   comm) const
  {
    TrilinosWrappers::SparsityPattern pattern =
      NewtonSystem::border_pattern(locally_owned, locally_relevant, particles.n_unknowns(), comm);
    if (particles.n_unknowns() == 0)
      return pattern;
    // Rows: the multiplier DoFs (the pairing, doc/method.md §3) and the velocity DoFs (the
    // kinematic closure's ∂ω/∂u); the pressure has no particle coupling.
    std::vector<unsigned int> coupled;
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      if (Introspection<dim>::field(fe.system_to_component_index(i).first) !=
          Introspection<dim>::Field::pressure)
        coupled.push_back(i);
    const AffineConstraints<double>      no_constraints;
    std::vector<types::global_dof_index> dof_indices(fe.n_dofs_per_cell()), rows(coupled.size());
    for (const auto &[cell, k] : support.free_particle_cells)
      {
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < coupled.size(); ++i)
          rows[i] = dof_indices[coupled[i]];
        constraints.add_entries_local_to_global(rows, no_constraints, unknowns_of(particles[k]),
                                                pattern, /*keep_constrained_entries=*/false);
      }
    pattern.compress();
    return pattern;
  }

  template <int dim>
  Vector<float> NavierStokesAssembler<dim>::particle_fraction(const DoFHandler<dim> &dof_handler) const
  {
    Vector<float> fraction(dof_handler.get_triangulation().n_active_cells());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        fraction[cell->active_cell_index()] = quadrature.particle_fraction(cell, particles, mapping);
    return fraction;
  }

  template class NavierStokesAssembler<2>;
  template class NavierStokesAssembler<3>;
} // namespace fdparticle
