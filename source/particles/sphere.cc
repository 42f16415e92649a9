#include <deal.II/base/numbers.h>
#include <deal.II/base/symmetric_tensor.h>

#include <fdparticle/particles/sphere.h>

#include <cmath>

namespace fdparticle
{
  namespace
  {
    /// ψ(x) = |x − X|² − R², the sphere's level set.
    template <int dim>
    class SphereLevelSet : public Function<dim>
    {
    public:
      SphereLevelSet(const Point<dim> &center, const double radius)
        : center(center)
        , radius(radius)
      {}
      double value(const Point<dim> &x, const unsigned int = 0) const override
      {
        return (x - center).norm_square() - radius * radius;
      }
      Tensor<1, dim> gradient(const Point<dim> &x, const unsigned int = 0) const override
      {
        return 2.0 * (x - center);
      }
      SymmetricTensor<2, dim> hessian(const Point<dim> &, const unsigned int = 0) const override
      {
        return 2.0 * unit_symmetric_tensor<dim>();
      }

    private:
      const Point<dim> center;
      const double     radius;
    };
  } // namespace

  template <int dim>
  Sphere<dim>::Sphere(const double radius)
    : R(radius)
  {}

  template <int dim>
  double Sphere<dim>::volume() const
  {
    return (dim == 2 ? numbers::PI * R * R : 4.0 / 3.0 * numbers::PI * R * R * R);
  }

  template <int dim>
  Tensor<2, 3> Sphere<dim>::inertia() const
  {
    return Tensor<2, 3>((dim == 2 ? 0.5 : 0.4) * volume() * R * R * unit_symmetric_tensor<3>());
  }

  template <int dim>
  bool Sphere<dim>::contains(const Tensor<1, dim> &r) const
  {
    // Squares: the same test without a root, per quadrature point of a cut cell.
    constexpr double t = Shape<dim>::surface_tolerance;
    return r.norm_square() < R * R * (1 + t) * (1 + t);
  }

  template <int dim>
  std::unique_ptr<Function<dim>> Sphere<dim>::level_set(const Point<dim> &X,
                                                       const Tensor<2, dim> &) const
  {
    return std::make_unique<SphereLevelSet<dim>>(X, R);
  }

  template <int dim>
  bool Sphere<dim>::has_height_direction(const BoundingBox<dim> &box, const Point<dim> &X,
                                         const Tensor<2, dim> &, const double min_slope) const
  {
    double far2 = 0, gap = 0;
    for (unsigned int d = 0; d < dim; ++d)
      {
        far2 += std::pow(std::max(X[d] - box.lower_bound(d), box.upper_bound(d) - X[d]), 2);
        gap = std::max(gap, std::max(box.lower_bound(d) - X[d], X[d] - box.upper_bound(d)));
      }
    return gap >= min_slope * std::sqrt(far2);
  }

  template class Sphere<2>;
  template class Sphere<3>;
} // namespace fdparticle
