#ifndef fdparticle_particles_sphere_h
#define fdparticle_particles_sphere_h

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
    double      radius() const { return R; }

    double bounding_radius() const override { return R; }
    double inscribed_radius() const override { return R; }
    /// πR² (2D), 4/3 πR³ (3D).
    double volume() const override;
    /// (1/2)|P|R² (disk), (2/5)|P|R² (sphere).
    double inertia() const override;

    bool   contains(const Tensor<1, dim> &r) const override;
    double surface_distance(const Tensor<1, dim> &r) const override { return r.norm() - R; }

    /// ψ(x) = |x − X|² − R²: smooth everywhere (unlike the signed distance, whose
    /// gradient is singular at the centre a small ball's cell contains).
    std::unique_ptr<Function<dim>> level_set(const Point<dim> &X) const override;

  private:
    double R;
  };
} // namespace fdparticle

#endif
