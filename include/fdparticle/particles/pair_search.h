#ifndef fdparticle_particles_pair_search_h
#define fdparticle_particles_pair_search_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <fdparticle/base/box.h>

#include <array>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The pairs of balls whose surfaces are closer than a given reach, found with a
   * CellList: the bins are at least as wide as the largest centre distance that can be
   * within reach, so a ball is compared only with the balls of its own and the adjacent
   * bins. That is O(N) work for N balls spread over the box, instead of the N²/2
   * comparisons of all pairs. In a periodic direction the distance is to the nearest
   * periodic image.
   */
  template <int dim>
  class PairSearch
  {
  public:
    explicit PairSearch(const Box<dim> &domain);

    struct Pair
    {
      unsigned int i, j; ///< i < j
      /// x_i − x_j, to the nearest periodic image of x_j.
      Tensor<1, dim> offset;
      /// |offset| − r_i − r_j: negative if the balls overlap.
      double gap;
    };

    /// Every pair (i < j) of the balls (centres x, radii r) whose gap is below reach, once.
    std::vector<Pair> pairs(const std::vector<Point<dim>> &x, const std::vector<double> &r,
                            const double reach) const;

  private:
    Box<dim> domain;
  };
} // namespace fdparticle

#endif
