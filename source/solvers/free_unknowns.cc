#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/free_unknowns.h>

namespace fdparticle
{
  FreeUnknowns::FreeUnknowns(const BorderedOperator &op, const NewtonSystem &system)
    : op(op)
    , free_dofs(system.blocks.free_dofs)
    , n_all(system.r_fe.size())
  {
    // Each rank's free unknowns follow those of the ranks before it.
    const MPI_Comm comm = system.r_fe.get_mpi_communicator();
    layout = Utilities::MPI::create_ascending_partitioning(
      comm, free_dofs.size())[Utilities::MPI::this_mpi_process(comm)];
    op.reinit_vector(wide_src);
    op.reinit_vector(wide_dst);
  }

  void FreeUnknowns::reinit_vector(BlockVector &v) const
  {
    v.reinit(std::vector<IndexSet>{layout, op.particle_layout()},
             wide_src.block(0).get_mpi_communicator());
  }

  void FreeUnknowns::restrict(const BlockVector &full, BlockVector &v) const
  {
    const double *f = full.block(0).trilinos_vector()[0];
    double *      r = v.block(0).trilinos_vector()[0];
    for (std::size_t i = 0; i < free_dofs.size(); ++i)
      r[i] = f[free_dofs[i]];
    v.block(1) = full.block(1);
  }

  void FreeUnknowns::extend(const BlockVector &v, BlockVector &full) const
  {
    const double *r = v.block(0).trilinos_vector()[0];
    double *      f = full.block(0).trilinos_vector()[0];
    for (std::size_t i = 0; i < free_dofs.size(); ++i)
      f[free_dofs[i]] = r[i];
    full.block(1) = v.block(1);
  }
} // namespace fdparticle
