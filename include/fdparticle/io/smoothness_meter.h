#ifndef fdparticle_io_smoothness_meter_h
#define fdparticle_io_smoothness_meter_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/tensor.h>

#include <fdparticle/particles/particle_set.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Roughness of each particle's velocity history (doc/method.md, "Smoothness measure"):
   *
   *   S = RMS_n |V_{n+1} − 2 V_n + V_{n−1}|  /  RMS_n |V_n|
   *
   * over the steps after the start-up (the first max(3, N/10) steps of N are left out: the
   * start from rest is not smooth at any resolution). A smoothly sampled curve gives
   * S ≈ Δt² |V''|/|V| ≪ 1; a jump of relative size j every m steps gives S ≈ j √(2/m).
   * (Not the ratio to the first difference: near terminal velocity V' ≈ 0 and any
   * wiggle, however small, makes that ratio O(1).) The definition is fixed so that runs can
   * be compared.
   */
  template <int dim>
  class SmoothnessMeter
  {
  public:
    /// Record the velocities of all particles after a step (call on every rank).
    void record(const ParticleSet<dim> &particles);

    /// S of particle k (0 if the run is too short to tell).
    double smoothness(const unsigned int k) const;

    /// Print one line per particle and write DIRECTORY/smoothness.csv (rank 0).
    void write(const std::string &directory, ConditionalOStream &pcout, const bool root) const;

    /// The recorded history, for checkpoints (exact text).
    void save(std::ostream &out) const;
    void load(std::istream &in);

  private:
    std::vector<std::vector<Tensor<1, dim>>> history; // [particle][step]
  };
} // namespace fdparticle

#endif
