#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_system.h>

#include <fdparticle/fem/block_numbering.h>
#include <fdparticle/fem/introspection.h>
#include <fdparticle/particles/rigid_body.h>

namespace fdparticle
{
  template <int dim>
  void number_dofs_by_block(DoFHandler<dim> &dof_handler, const bool cell_pressure_masses,
                            NewtonSystem::Blocks &b)
  {
    const FiniteElement<dim> &fe   = dof_handler.get_fe();
    const MPI_Comm            comm = dof_handler.get_communicator();
    // Each rank numbers its own DoFs u | λ | p, keeping its contiguous range (deal.II's
    // parallel vectors and DataOut need one range per rank; component_wise would number
    // the blocks across the ranks). Within a block the old order is kept: u and λ of one
    // node are neighbours in it (FESystem), so velocity DoF i and multiplier DoF i of a
    // rank sit at the same node and component.
    const IndexSet                 owned = dof_handler.locally_owned_dofs();
    Assert(owned.is_contiguous(), ExcInternalError());
    using Blocks = NewtonSystem::Blocks;
    // A DoF's block is its field: both list u, λ, p in this order.
    static_assert(static_cast<unsigned int>(Introspection<dim>::Field::pressure) == Blocks::pressure,
                  "the blocks must follow the order of the fields");
    std::vector<unsigned int>      block(owned.n_elements(), 0);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < dofs.size(); ++i)
            if (owned.is_element(dofs[i]))
              block[owned.index_within_set(dofs[i])] =
                static_cast<unsigned int>(Introspection<dim>::field(fe.system_to_component_index(i).first));
        }
    std::array<types::global_dof_index, Blocks::n_blocks> count{};
    for (const unsigned int b : block)
      ++count[b];
    std::array<types::global_dof_index, Blocks::n_blocks + 1> range{};
    range[0] = owned.n_elements() > 0 ? *owned.begin() : 0;
    for (unsigned int b = 0; b < Blocks::n_blocks; ++b)
      range[b + 1] = range[b] + count[b];
    std::vector<types::global_dof_index> new_numbers(owned.n_elements());
    std::array<types::global_dof_index, Blocks::n_blocks> next{};
    std::copy(range.begin(), range.begin() + Blocks::n_blocks, next.begin());
    for (unsigned int k = 0; k < block.size(); ++k)
      new_numbers[k] = next[block[k]]++;
    dof_handler.renumber_dofs(new_numbers);

    b.range = Utilities::MPI::all_gather(comm, range);
    b.offset.assign(b.range.size(), {});
    for (std::size_t r = 1; r < b.range.size(); ++r)
      for (unsigned int k = 0; k < Blocks::n_blocks; ++k)
        b.offset[r][k] = b.offset[r - 1][k] + (b.range[r - 1][k + 1] - b.range[r - 1][k]);
    DoFTools::extract_constant_modes(dof_handler,
                                     fe.component_mask(Introspection<dim>::velocities()),
                                     b.velocity_modes);
    b.particle_block_size = RigidBody<dim>::n_unknowns;

    // The block solver reads the pairing matrix off the λ–u block of A (see above); it
    // would precondition with nonsense if the pairing of the numbers broke, so check it.
    const types::global_dof_index shift = range[Blocks::multiplier] - range[Blocks::velocity];
    AssertThrow(range[Blocks::pressure] - range[Blocks::multiplier] == shift, ExcInternalError());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
            {
              const auto [component, index] = fe.system_to_component_index(i);
              if (Introspection<dim>::field(component) != Introspection<dim>::Field::velocity ||
                  dofs[i] < range[Blocks::velocity] || dofs[i] >= range[Blocks::multiplier])
                continue;
              const unsigned int j = fe.component_to_system_index(component + dim, index);
              AssertThrow(dofs[j] == dofs[i] + shift, ExcInternalError());
            }
        }

    // 0 tells the assembler to skip the cell pressure masses, which only some solvers read.
    b.pressure_dofs_per_cell =
      cell_pressure_masses ?
        fe.base_element(fe.component_to_base_index(Introspection<dim>::pressure_component).first)
          .n_dofs_per_cell() :
        0;
  }

  template void number_dofs_by_block(DoFHandler<2> &, const bool, NewtonSystem::Blocks &);
  template void number_dofs_by_block(DoFHandler<3> &, const bool, NewtonSystem::Blocks &);
} // namespace fdparticle
