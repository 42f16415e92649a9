#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <fdparticle/fem/introspection.h>
#include <fdparticle/fem/velocity_block.h>

namespace fdparticle
{
  namespace
  {
    /// For each owned DoF of velocity_dofs (a velocity-only DoFHandler on the system's
    /// mesh), its place among the system's owned DoFs, whose first is first_owned; both
    /// numberings must give each DoF the same owner.
    template <int dim>
    std::vector<unsigned int> system_positions(const DoFHandler<dim> &        velocity_dofs,
                                               const DoFHandler<dim> &        system_dofs,
                                               const types::global_dof_index first_owned)
    {
      // From the cells both share: velocity component c, scalar function a in each.
      const FiniteElement<dim> &fe = velocity_dofs.get_fe(), &system_fe = system_dofs.get_fe();
      const IndexSet            owned        = velocity_dofs.locally_owned_dofs();
      const IndexSet            system_owned = system_dofs.locally_owned_dofs();
      std::vector<unsigned int> position(owned.n_elements(), numbers::invalid_unsigned_int);
      std::vector<types::global_dof_index> system_cell_dofs(system_fe.n_dofs_per_cell()),
        cell_dofs(fe.n_dofs_per_cell());
      const unsigned int n_scalar = fe.base_element(0).n_dofs_per_cell();
      for (const auto &cell : velocity_dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(cell_dofs);
            typename DoFHandler<dim>::active_cell_iterator(&system_dofs.get_triangulation(),
                                                           cell->level(), cell->index(),
                                                           &system_dofs)
              ->get_dof_indices(system_cell_dofs);
            for (unsigned int c = 0; c < dim; ++c)
              for (unsigned int a = 0; a < n_scalar; ++a)
                {
                  const auto v = cell_dofs[fe.component_to_system_index(c, a)];
                  if (!owned.is_element(v))
                    continue;
                  const auto s = system_cell_dofs[system_fe.component_to_system_index(
                    Introspection<dim>::first_velocity_component + c, a)];
                  AssertThrow(system_owned.is_element(s),
                              ExcMessage("The matrix-free velocity block needs each velocity "
                                         "DoF owned by the same rank in both numberings."));
                  position[owned.index_within_set(v)] = s - first_owned;
                }
          }
      return position;
    }
  } // namespace

  template <int dim>
  void make_velocity_constraints(const Domain<dim> &domain, const DoFHandler<dim> &velocity_dofs,
                                 AffineConstraints<double> &constraints)
  {
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(velocity_dofs, relevant);
    constraints.clear();
    constraints.reinit(relevant);
    DoFTools::make_hanging_node_constraints(velocity_dofs, constraints);
    domain.make_periodicity_constraints(velocity_dofs, constraints);
    domain.make_wall_constraints(velocity_dofs, ComponentMask(dim, true), true, constraints);
    constraints.close();
  }

  template <int dim>
  VelocityBlock<dim>::VelocityBlock(const Mapping<dim> &mapping, const Domain<dim> &domain)
    : mapping(mapping)
    , domain(domain)
    , fe(FE_Q<dim>(VelocityOperator<dim>::degree), dim)
  {}

  template <int dim>
  void VelocityBlock<dim>::reinit(const DoFHandler<dim> &system_dofs,
                                  const NewtonSystem::Blocks &blocks,
                                  const AffineConstraints<double> &constraints)
  {
    this->system_dofs        = &system_dofs;
    this->blocks             = &blocks;
    this->system_constraints = &constraints;
    first_owned = blocks.range[Utilities::MPI::this_mpi_process(system_dofs.get_communicator())][0];
    current = false;
  }

  template <int dim>
  void VelocityBlock<dim>::build()
  {
    velocity_dofs.reinit(system_dofs->get_triangulation());
    velocity_dofs.distribute_dofs(fe);
    make_velocity_constraints(domain, velocity_dofs, constraints);
    op.reinit(mapping, velocity_dofs, constraints);
    op.initialize_dof_vector(iterate);
    op.initialize_dof_vector(in);
    op.initialize_dof_vector(out);
    system_position = system_positions(velocity_dofs, *system_dofs, first_owned);
    const IndexSet &owned = velocity_dofs.locally_owned_dofs();
    unconstrained.clear();
    for (unsigned int i = 0; i < system_position.size(); ++i)
      if (!constraints.is_constrained(owned.nth_index_in_set(i)))
        unconstrained.push_back(i);
    const MatrixFree<dim, double> &data = op.get_matrix_free();
    batch_of_cell.assign(system_dofs->get_triangulation().n_active_cells(),
                         numbers::invalid_unsigned_int);
    for (unsigned int b = 0; b < data.n_cell_batches(); ++b)
      batch_of_cell[data.get_cell_iterator(b, 0)->active_cell_index()] = b;
    current = true;
  }

  template <int dim>
  void VelocityBlock<dim>::set_jacobian(const double density, const double viscosity,
                                        const double                         c0,
                                        const TrilinosWrappers::MPI::Vector *iterate_in,
                                        std::vector<FullMatrix<double>>      cut_matrices)
  {
    if (!current)
      build();
    this->density   = density;
    this->viscosity = viscosity;
    this->c0        = c0;
    convection      = iterate_in != nullptr;
    if (iterate_in != nullptr)
      {
        const double *values = iterate_in->trilinos_vector()[0];
        for (unsigned int i = 0; i < system_position.size(); ++i)
          iterate.local_element(i) = values[system_position[i]];
      }
    op.set_coefficients(density, viscosity, c0, iterate_in != nullptr ? &iterate : nullptr);
    op.set_cut_cell_matrices(std::move(cut_matrices));
  }

  template <int dim>
  void VelocityBlock<dim>::vmult_add(TrilinosWrappers::MPI::Vector &      dst,
                                     const TrilinosWrappers::MPI::Vector &src) const
  {
    Assert(current, ExcMessage("The velocity block has no Jacobian."));
    const double *s = src.trilinos_vector()[0];
    double *      d = dst.trilinos_vector()[0];
    for (unsigned int i = 0; i < system_position.size(); ++i)
      in.local_element(i) = s[system_position[i]];
    op.vmult(out, in);
    for (const unsigned int i : unconstrained)
      d[system_position[i]] += out.local_element(i);
  }

  template <int dim>
  void VelocityBlock<dim>::assemble_on_cells(const std::vector<bool> &        cells,
                                             TrilinosWrappers::SparseMatrix &matrix) const
  {
    Assert(current, ExcMessage("The velocity block has no Jacobian."));
    const MPI_Comm            comm      = system_dofs->get_communicator();
    const FiniteElement<dim> &system_fe = system_dofs->get_fe();
    const unsigned int        n_scalar  = fe.base_element(0).n_dofs_per_cell();
    const unsigned int        npc       = blocks->pressure_dofs_per_cell;
    const auto first_pressure = blocks->range[Utilities::MPI::this_mpi_process(comm)]
                                             [NewtonSystem::Blocks::pressure];
    const unsigned int p_local =
      system_fe.component_to_system_index(Introspection<dim>::pressure_component, 0);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(*system_dofs, relevant);
    const IndexSet &owned = system_dofs->locally_owned_dofs();

    // The marked cells and their velocity DoFs in the system, ordered as K's cell matrices
    // (component c, scalar function a) → c n + a.
    std::vector<std::pair<unsigned int, std::vector<types::global_dof_index>>> marked;
    std::vector<types::global_dof_index> dofs(system_fe.n_dofs_per_cell());
    for (const auto &cell : system_dofs->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          const unsigned int local = (dofs[p_local] - first_pressure) / npc;
          Assert(local < cells.size(), ExcInternalError());
          if (!cells[local])
            continue;
          std::vector<types::global_dof_index> velocity(dim * n_scalar);
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int a = 0; a < n_scalar; ++a)
              velocity[c * n_scalar + a] = dofs[system_fe.component_to_system_index(
                Introspection<dim>::first_velocity_component + c, a)];
          marked.emplace_back(batch_of_cell[cell->active_cell_index()], std::move(velocity));
        }
    TrilinosWrappers::SparsityPattern sparsity(owned, owned, relevant, comm);
    for (const auto &[batch, velocity] : marked)
      system_constraints->add_entries_local_to_global(velocity, sparsity, false);
    sparsity.compress();
    matrix.reinit(sparsity);
    FullMatrix<double> local;
    for (const auto &[batch, velocity] : marked)
      {
        op.cell_matrix(batch, local);
        system_constraints->distribute_local_to_global(local, velocity, matrix);
      }
    matrix.compress(VectorOperation::add);
    // The constraints put a diagonal into constrained rows; A holds those.
    std::vector<types::global_dof_index> constrained;
    for (const auto i : owned)
      if (system_constraints->is_constrained(i) &&
          blocks->locate(i).first == NewtonSystem::Blocks::velocity)
        constrained.push_back(i);
    matrix.clear_rows(constrained, 0.0);
  }

  template void make_velocity_constraints(const Domain<2> &, const DoFHandler<2> &,
                                          AffineConstraints<double> &);
  template void make_velocity_constraints(const Domain<3> &, const DoFHandler<3> &,
                                          AffineConstraints<double> &);
  template class VelocityBlock<2>;
  template class VelocityBlock<3>;
} // namespace fdparticle
