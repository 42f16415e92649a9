#include <fdparticle/fem/assembly/particle_integrals.h>

namespace fdparticle
{
  template <int dim>
  void ParticleIntegrals<dim>::sum_over_ranks(std::vector<ParticleIntegrals<dim>> &integrals,
                                              const MPI_Comm                        comm)
  {
    std::vector<double> packed;
    for (const auto &I : integrals)
      {
        for (unsigned int d = 0; d < dim; ++d)
          packed.push_back(I.lambda_force[d]);
        for (unsigned int d = 0; d < 3; ++d)
          packed.push_back(I.lambda_torque[d]);
        for (unsigned int d = 0; d < 3; ++d)
          packed.push_back(I.curl_u[d]);
        packed.push_back(I.volume);
      }
    Utilities::MPI::sum(packed, comm, packed);
    unsigned int pos = 0;
    for (auto &I : integrals)
      {
        for (unsigned int d = 0; d < dim; ++d)
          I.lambda_force[d] = packed[pos++];
        for (unsigned int d = 0; d < 3; ++d)
          I.lambda_torque[d] = packed[pos++];
        for (unsigned int d = 0; d < 3; ++d)
          I.curl_u[d] = packed[pos++];
        I.volume = packed[pos++];
      }
  }

  template struct ParticleIntegrals<2>;
  template struct ParticleIntegrals<3>;
} // namespace fdparticle
