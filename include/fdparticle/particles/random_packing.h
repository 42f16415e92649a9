#ifndef fdparticle_particles_random_packing_h
#define fdparticle_particles_random_packing_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <fdparticle/base/box.h>
#include <fdparticle/particles/particle_set.h>

#include <cstdint>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Free particles placed at random without overlap (subsection Particles/Random
   * particles), by random sequential addition: each draws its size (the radius of a ball,
   * the largest semi-axis of an ellipse or ellipsoid of the given axis ratios) and, unless
   * a ball, an orientation uniform over all rotations; then centres uniformly in the
   * sub-box, of which the first that keeps the minimum gap to the walls and to every
   * particle of the packing is taken (those of the particle list and file included):
   * bounding balls found with a CellList, the true gap (ContactGeometry) where they come
   * closer. The numbers come from a 64-bit Mersenne twister turned into doubles by this
   * class, not by a library distribution, so one seed gives the same particles on every
   * rank and every machine.
   */
  template <int dim>
  class RandomPacking
  {
  public:
    /// Declared inside subsection Particles.
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm, const Box<dim> &domain);

    /// The requested number of particles (0: none).
    unsigned int count() const { return n_particles; }

    /**
     * Draws of a centre per particle before placement gives up. Random sequential
     * addition of balls jams near a solid fraction of 0.55 (2D) and 0.38 (3D), where the
     * free area left to a centre shrinks to nothing; 10^4 draws find a place while one
     * exists in more than 1/10^4 of the sub-box, and stay cheap.
     */
    static constexpr unsigned int max_draws_per_particle = 10000;

    /// The free particles, placed around the given ones. Throws a one-line error if one
    /// finds no place in max_draws_per_particle draws (the sub-box is too full).
    std::vector<Particle<dim>> place(const std::vector<Particle<dim>> &existing) const;

  private:
    unsigned int  n_particles = 0;
    double        min_radius = 0, max_radius = 0, density = 0, min_gap = 0;
    /// The semi-axes relative to the largest (0: balls).
    Tensor<1, dim> axis_ratios;
    Point<dim>     lower, upper; // the sub-box
    std::uint64_t  seed = 0;
    Box<dim>       domain;
  };
} // namespace fdparticle

#endif
