#ifndef fdparticle_fem_assembly_particle_integrals_h
#define fdparticle_fem_assembly_particle_integrals_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /// Integrals over one ball that its equations (F4)–(F5) and its reported force and
  /// torque need (doc/method.md §0, §9). The cell loop sums them on each rank.
  template <int dim>
  struct ParticleIntegrals
  {
    Tensor<1, dim> lambda_force;  ///< <λ, e_i>_P = ∫_P κ λ_i
    Tensor<1, 3>   lambda_torque; ///< <λ, e_j × r>_P
    Tensor<1, 3>   curl_u;        ///< ∫_P ∇ × u
    double         volume = 0;    ///< ∫_P 1 by the cut-cell rule

    /// Sum the integrals of every particle over all ranks, in one message.
    static void sum_over_ranks(std::vector<ParticleIntegrals<dim>> &integrals,
                               const MPI_Comm                        comm);
  };
} // namespace fdparticle

#endif
