#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <fdparticle/solvers/bordered_operator.h>

#include <algorithm>
#include <vector>

namespace fdparticle
{
  BorderedOperator::BorderedOperator(const NewtonSystem &system)
    : system(system)
    , particle_dofs(NewtonSystem::particle_unknowns(system.n_particle_unknowns(),
                                                    system.r_fe.get_mpi_communicator()))
  {}

  void BorderedOperator::reinit_vector(BlockVector &v) const
  {
    v.reinit(std::vector<IndexSet>{system.r_fe.locally_owned_elements(), particle_dofs},
             system.r_fe.get_mpi_communicator());
  }

  Eigen::VectorXd BorderedOperator::particle_part(const BlockVector &v) const
  {
    const unsigned int  m = n_particle_unknowns();
    std::vector<double> y(m, 0.0);
    const MPI_Comm      comm = system.r_fe.get_mpi_communicator();
    if (Utilities::MPI::this_mpi_process(comm) == 0 && m > 0)
      std::copy_n(v.block(1).trilinos_vector()[0], m, y.data());
    y = Utilities::MPI::broadcast(comm, y, 0);
    return Eigen::Map<const Eigen::VectorXd>(y.data(), m);
  }

  void BorderedOperator::set_particle_part(BlockVector &v, const Eigen::VectorXd &y) const
  {
    if (Utilities::MPI::this_mpi_process(system.r_fe.get_mpi_communicator()) == 0 &&
        y.size() > 0)
      std::copy_n(y.data(), y.size(), v.block(1).trilinos_vector()[0]);
  }

  void BorderedOperator::vmult(BlockVector &dst, const BlockVector &src) const
  {
    const Timer           timer;
    const Eigen::VectorXd y     = particle_part(src);
    system.A.vmult(dst.block(0), src.block(0));
    if (system.blocks.velocity_product)
      system.blocks.velocity_product->vmult_add(dst.block(0), src.block(0));
    system.add_border(y, dst.block(0));
    set_particle_part(dst, system.border_product(src.block(0)) + system.D * y);
    vmult_seconds += timer.wall_time();
  }
} // namespace fdparticle
