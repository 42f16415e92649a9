#ifndef fdparticle_fem_block_numbering_h
#define fdparticle_fem_block_numbering_h

#include <deal.II/dofs/dof_handler.h>

#include <fdparticle/solvers/newton_system.h>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Renumber each rank's DoFs block by block, u | λ | p, and describe the layout in b
   * (ranges, offsets, velocity modes, particle block size; doc/method.md §8). The λ–u
   * pairing the block solver relies on is checked. cell_pressure_masses: the linear
   * solver reads the cells' pressure mass matrices (LinearSolver::assembled_data), so the
   * assembler is told their size.
   */
  template <int dim>
  void number_dofs_by_block(DoFHandler<dim> &dof_handler, const bool cell_pressure_masses,
                            NewtonSystem::Blocks &b);
} // namespace fdparticle

#endif
