#ifndef fdparticle_particles_random_packing_h
#define fdparticle_particles_random_packing_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <fdparticle/base/box.h>

#include <cstdint>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Free balls placed at random without overlap (subsection Particles/Random particles),
   * by random sequential addition: each ball draws its radius, then centres uniformly in
   * the sub-box until one keeps the minimum gap to the walls and to every ball placed
   * before it (the balls of the particle list and file included), found with a CellList.
   * The numbers come from a 64-bit Mersenne twister turned into doubles by this class,
   * not by a library distribution, so one seed gives the same balls on every rank and
   * every machine.
   */
  template <int dim>
  class RandomPacking
  {
  public:
    /// Declared inside subsection Particles.
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm, const Box<dim> &domain);

    /// The requested number of balls (0: none).
    unsigned int count() const { return n_balls; }

    struct Ball
    {
      Point<dim> center;
      double     radius;
    };

    /**
     * Draws of a centre per ball before placement gives up. Random sequential addition
     * jams near a solid fraction of 0.55 (2D) and 0.38 (3D), where the free area left to
     * a centre shrinks to nothing; 10^4 draws find a place while one exists in more than
     * 1/10^4 of the sub-box, and stay cheap.
     */
    static constexpr unsigned int max_draws_per_ball = 10000;

    /// The balls, placed around the given ones. Throws a one-line error if a ball finds
    /// no place in max_draws_per_ball draws (the sub-box is too full).
    std::vector<Ball> place(const std::vector<Ball> &existing) const;

    double density() const { return ball_density; }

  private:
    unsigned int  n_balls = 0;
    double        min_radius = 0, max_radius = 0, ball_density = 0, min_gap = 0;
    Point<dim>    lower, upper; // the sub-box
    std::uint64_t seed = 0;
    Box<dim>   domain;
  };
} // namespace fdparticle

#endif
