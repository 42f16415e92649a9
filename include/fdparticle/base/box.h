#ifndef fdparticle_base_box_h
#define fdparticle_base_box_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The box Ω as geometry: its corners (subsection Geometry) and what bounds it in each
   * direction (periodic, or two no-slip walls that may slide; subsection Boundary
   * conditions). Particles, contacts and the pair search ask it for walls, periods and
   * nearest images; the mesh on it is fem/Domain's. Faces are numbered 0..2dim-1 in the
   * order x-, x+, y-, y+, z-, z+ (the mesh's boundary ids).
   */
  template <int dim>
  class Box
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    /**
     * The largest coordinate, and the inverse of the narrowest box, accepted. Lengths enter
     * squared and cubed (cell volumes, |x - X|^2) and are multiplied by densities,
     * viscosities and 1/dt: beyond 1e+-30 a scene leaves the range of double (1e+-308)
     * and the run ends in overflow. A light year is 1e16 m, a nanometre 1e-9 m: any scene
     * in any unit lies inside.
     */
    static constexpr double max_length = 1e30;

    /// A wall near a ball: the gap between them, the wall's inward normal and its
    /// (tangential) velocity.
    struct WallGap
    {
      double         gap;
      Tensor<1, dim> normal, velocity;
    };
    /// The walls whose gap to the ball of centre x and radius r is below reach.
    std::vector<WallGap> walls_near(const Point<dim> &x, const double r, const double reach) const;

    bool           is_periodic(const unsigned int direction) const { return periodic[direction]; }
    /// The box's length in each periodic direction, 0 in the wall-bounded ones.
    Tensor<1, dim> period() const;
    /// r shifted by whole periods (period as given by period()) to its shortest image:
    /// the nearest-image rule of every distance in a periodic box (doc/method.md §12).
    static Tensor<1, dim> nearest_image(Tensor<1, dim> r, const Tensor<1, dim> &period)
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (period[d] > 0)
          r[d] -= period[d] * std::round(r[d] / period[d]);
      return r;
    }
    bool               is_wall(const types::boundary_id face) const;
    Tensor<1, dim>     wall_velocity(const types::boundary_id face) const;
    const Point<dim> & lower_corner() const { return lower; }
    const Point<dim> & upper_corner() const { return upper; }
    double             volume() const;
    /// The non-constant eigenmodes of the Laplacian on the box (Neumann on the walls,
    /// periodic across periodic faces) with a wavenumber below k, counted up to cap: the
    /// modes exp(i k·x) or cos(k·x) with k_d = π m/L_d (walls, m ≥ 0) or 2π m/L_d
    /// (periodic, m of either sign).
    unsigned int       count_modes_below(const double k, const unsigned int cap) const;
    static std::string face_name(const types::boundary_id face);

  protected:
    Point<dim>                          lower, upper;
    std::array<bool, dim>               periodic{};
    std::array<Tensor<1, dim>, 2 * dim> wall_velocities{};
  };
} // namespace fdparticle

#endif
