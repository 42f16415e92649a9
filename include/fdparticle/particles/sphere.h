#ifndef fdparticle_particles_sphere_h
#define fdparticle_particles_sphere_h

#include <deal.II/base/symmetric_tensor.h>

#include <fdparticle/particles/shape.h>

namespace fdparticle
{
  /// A ball of radius R: a sphere in 3D, a disk in 2D.
  template <int dim>
  class Sphere : public Shape<dim>
  {
  public:
    explicit Sphere(const double radius);

    std::string name() const override { return dim == 2 ? "disk" : "sphere"; }
    bool        is_isotropic() const override { return true; }
    double      radius() const { return R; }

    double bounding_radius() const override { return R; }
    Tensor<2, dim> semi_axes_tensor() const override { return R * unit_symmetric_tensor<dim>(); }
    double inscribed_radius() const override { return R; }
    /// πR² (2D), 4/3 πR³ (3D).
    double volume() const override;
    /// (1/2)|P|R² (disk), (2/5)|P|R² (sphere) times the identity.
    Tensor<2, 3> inertia() const override;

    bool   contains(const Tensor<1, dim> &r) const override;
    Tensor<1, dim> support_point(const Tensor<1, dim> &n) const override { return R * n; }
    double surface_distance(const Tensor<1, dim> &r) const override { return r.norm() - R; }

    /// ψ(x) = |x − X|² − R²: smooth everywhere (unlike the signed distance, whose
    /// gradient is singular at the centre a small ball's cell contains).
    std::unique_ptr<Function<dim>> level_set(const Point<dim> &X,
                                             const Tensor<2, dim> &Q) const override;

    /// The bounding ball is the ball: a box within it meets it.
    bool meets(const BoundingBox<dim> &, const Point<dim> &, const Tensor<2, dim> &) const override
    {
      return true;
    }

    /// ∂ψ/∂x_d = 2(x_d − X_d): a direction in which the box lies wholly on one side of X,
    /// by at least min_slope times the farthest corner's distance.
    bool has_height_direction(const BoundingBox<dim> &box, const Point<dim> &X,
                              const Tensor<2, dim> &Q, const double min_slope) const override;

  private:
    double R;
  };
} // namespace fdparticle

#endif
