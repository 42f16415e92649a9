#ifndef fdparticle_particles_ellipsoid_h
#define fdparticle_particles_ellipsoid_h

#include <fdparticle/particles/shape.h>

namespace fdparticle
{
  /**
   * An ellipsoid (3D) or ellipse (2D) with semi-axes a_i along the body axes e_i:
   * Σ_i (r_i/a_i)² ≤ 1 for a body offset r. Its level set in the world,
   * ψ(x) = (x − X)ᵀ A (x − X) − 1 with A = Q diag(1/a_i²) Qᵀ, is smooth everywhere.
   */
  template <int dim>
  class Ellipsoid : public Shape<dim>
  {
  public:
    /// Throws a one-line error naming 'name' if a semi-axis is not positive.
    Ellipsoid(const Tensor<1, dim> &semi_axes, const std::string &name);

    std::string name() const override { return dim == 2 ? "ellipse" : "ellipsoid"; }
    bool        is_isotropic() const override { return false; }

    double bounding_radius() const override;
    Tensor<2, dim> semi_axes_tensor() const override
    {
      Tensor<2, dim> S;
      for (unsigned int d = 0; d < dim; ++d)
        S[d][d] = a[d];
      return S;
    }
    double inscribed_radius() const override;
    /// π a_0 a_1 (2D), 4/3 π a_0 a_1 a_2 (3D).
    double volume() const override;
    /// |P|/5 diag(a_1² + a_2², a_0² + a_2², a_0² + a_1²) (3D); (|P|/4)(a_0² + a_1²) about
    /// z in 2D.
    Tensor<2, 3> inertia() const override;

    bool   contains(const Tensor<1, dim> &r) const override;
    /// diag(a_i²) n / (nᵀ diag(a_i²) n)^{1/2}.
    Tensor<1, dim> support_point(const Tensor<1, dim> &n) const override;
    double surface_distance(const Tensor<1, dim> &r) const override;
    /// The minimum of ψ over the box, by exact minimization along one coordinate at a time
    /// (ψ is a convex quadratic), is below zero.
    bool meets(const BoundingBox<dim> &box, const Point<dim> &X,
               const Tensor<2, dim> &Q) const override;
    std::unique_ptr<Function<dim>> level_set(const Point<dim> &X,
                                             const Tensor<2, dim> &Q) const override;
    /// ∇ψ = 2 A (x − X) is linear in x: its range on the box is that of its corners.
    bool has_height_direction(const BoundingBox<dim> &box, const Point<dim> &X,
                              const Tensor<2, dim> &Q, const double min_slope) const override;

  private:
    Tensor<1, dim> a;
    /// A = Q diag(1/a_i²) Qᵀ.
    Tensor<2, dim> level_set_matrix(const Tensor<2, dim> &Q) const;
  };
} // namespace fdparticle

#endif
