#include <deal.II/base/numbers.h>
#include <deal.II/base/symmetric_tensor.h>

#include <fdparticle/particles/ellipsoid.h>

#include <algorithm>
#include <cmath>

namespace fdparticle
{
  namespace
  {
    /// ψ(x) = (x − X)ᵀ A (x − X) − 1.
    template <int dim>
    class QuadraticLevelSet : public Function<dim>
    {
    public:
      QuadraticLevelSet(const Point<dim> &center, const Tensor<2, dim> &A)
        : center(center)
        , A(A)
      {}
      double value(const Point<dim> &x, const unsigned int = 0) const override
      {
        const Tensor<1, dim> r = x - center;
        return r * (A * r) - 1.0;
      }
      Tensor<1, dim> gradient(const Point<dim> &x, const unsigned int = 0) const override
      {
        return 2.0 * (A * (x - center));
      }
      SymmetricTensor<2, dim> hessian(const Point<dim> &, const unsigned int = 0) const override
      {
        return symmetrize(2.0 * A);
      }

    private:
      const Point<dim>     center;
      const Tensor<2, dim> A;
    };
  } // namespace

  template <int dim>
  Ellipsoid<dim>::Ellipsoid(const Tensor<1, dim> &semi_axes, const std::string &name)
    : a(semi_axes)
  {
    for (unsigned int d = 0; d < dim; ++d)
      AssertThrow(a[d] > 0 && std::isfinite(a[d]),
                  ExcMessage("Parameter '" + name + "': the semi-axes of an " + this->name() +
                             " must be positive, got " + std::to_string(a[d]) + "."));
  }

  template <int dim>
  double Ellipsoid<dim>::bounding_radius() const
  {
    double r = 0;
    for (unsigned int d = 0; d < dim; ++d)
      r = std::max(r, a[d]);
    return r;
  }

  template <int dim>
  double Ellipsoid<dim>::inscribed_radius() const
  {
    double r = a[0];
    for (unsigned int d = 1; d < dim; ++d)
      r = std::min(r, a[d]);
    return r;
  }

  template <int dim>
  double Ellipsoid<dim>::volume() const
  {
    return dim == 2 ? numbers::PI * a[0] * a[1] : 4.0 / 3.0 * numbers::PI * a[0] * a[1] * a[dim - 1];
  }

  template <int dim>
  Tensor<2, 3> Ellipsoid<dim>::inertia() const
  {
    Tensor<2, 3> J;
    if (dim == 2)
      {
        J[0][0] = volume() * a[1] * a[1] / 4;
        J[1][1] = volume() * a[0] * a[0] / 4;
        J[2][2] = volume() * (a[0] * a[0] + a[1] * a[1]) / 4;
      }
    else
      for (unsigned int i = 0; i < 3; ++i)
        {
          const double b = a[(i + 1) % dim], c = a[(i + 2) % dim];
          J[i][i] = volume() * (b * b + c * c) / 5;
        }
    return J;
  }

  template <int dim>
  bool Ellipsoid<dim>::contains(const Tensor<1, dim> &r) const
  {
    constexpr double t = Shape<dim>::surface_tolerance;
    double           s = 0;
    for (unsigned int d = 0; d < dim; ++d)
      s += (r[d] / a[d]) * (r[d] / a[d]);
    return s < (1 + t) * (1 + t);
  }

  template <int dim>
  Tensor<1, dim> Ellipsoid<dim>::support_point(const Tensor<1, dim> &n) const
  {
    Tensor<1, dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = a[d] * a[d] * n[d];
    return p / std::sqrt(p * n);
  }

  template <int dim>
  double Ellipsoid<dim>::surface_distance(const Tensor<1, dim> &r) const
  {
    double s = 0;
    for (unsigned int d = 0; d < dim; ++d)
      s += (r[d] / a[d]) * (r[d] / a[d]);
    s = std::sqrt(s);
    // The surface point on the ray from the centre through r is r/s.
    return s > 0 ? r.norm() * (1 - 1 / s) : -inscribed_radius();
  }

  template <int dim>
  Tensor<2, dim> Ellipsoid<dim>::level_set_matrix(const Tensor<2, dim> &Q) const
  {
    Tensor<2, dim> S;
    for (unsigned int d = 0; d < dim; ++d)
      S[d][d] = 1 / (a[d] * a[d]);
    return Q * S * transpose(Q);
  }

  template <int dim>
  bool Ellipsoid<dim>::meets(const BoundingBox<dim> &box, const Point<dim> &X,
                             const Tensor<2, dim> &Q) const
  {
    // Minimize ψ over the box coordinate by coordinate, each step exact and clamped to
    // the box (converges for a convex quadratic); stop as soon as a point is inside by
    // more than the tolerance. ψ ≈ 2 δ/a near the surface, δ the distance to it.
    const Tensor<2, dim> A = level_set_matrix(Q);
    const double threshold = -2 * Shape<dim>::surface_tolerance;
    Tensor<1, dim> y, lo, hi;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lo[d] = box.lower_bound(d) - X[d];
        hi[d] = box.upper_bound(d) - X[d];
        y[d] = std::clamp(0.0, lo[d], hi[d]);
      }
    double psi = y * (A * y) - 1;
    for (unsigned int sweep = 0; sweep < 200 && psi >= threshold; ++sweep)
      {
        double change = 0;
        for (unsigned int d = 0; d < dim; ++d)
          {
            double off = 0;
            for (unsigned int e = 0; e < dim; ++e)
              if (e != d)
                off += A[d][e] * y[e];
            const double next = std::clamp(-off / A[d][d], lo[d], hi[d]);
            change = std::max(change, std::abs(next - y[d]));
            y[d] = next;
          }
        psi = y * (A * y) - 1;
        if (change <= 1e-14 * inscribed_radius())
          break;
      }
    return psi < threshold;
  }

  template <int dim>
  std::unique_ptr<Function<dim>> Ellipsoid<dim>::level_set(const Point<dim> &X,
                                                          const Tensor<2, dim> &Q) const
  {
    return std::make_unique<QuadraticLevelSet<dim>>(X, level_set_matrix(Q));
  }

  template <int dim>
  bool Ellipsoid<dim>::has_height_direction(const BoundingBox<dim> &box, const Point<dim> &X,
                                            const Tensor<2, dim> &Q, const double min_slope) const
  {
    const Tensor<2, dim> A = level_set_matrix(Q);
    Tensor<1, dim>       lowest, highest;
    double               largest = 0;
    for (unsigned int v = 0; v < (1u << dim); ++v)
      {
        Tensor<1, dim> r;
        for (unsigned int d = 0; d < dim; ++d)
          r[d] = ((v >> d) & 1 ? box.upper_bound(d) : box.lower_bound(d)) - X[d];
        const Tensor<1, dim> g = A * r;
        largest = std::max(largest, g.norm());
        for (unsigned int d = 0; d < dim; ++d)
          {
            lowest[d] = (v == 0 ? g[d] : std::min(lowest[d], g[d]));
            highest[d] = (v == 0 ? g[d] : std::max(highest[d], g[d]));
          }
      }
    double gap = 0;
    for (unsigned int d = 0; d < dim; ++d)
      gap = std::max({gap, lowest[d], -highest[d]});
    return gap >= min_slope * largest;
  }

  template class Ellipsoid<2>;
  template class Ellipsoid<3>;
} // namespace fdparticle
