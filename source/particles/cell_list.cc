#include <fdparticle/particles/cell_list.h>

#include <cmath>

namespace fdparticle
{
  namespace
  {
    /// Bins per direction at most: keeps the bin keys small when the width is tiny
    /// against the box, at no cost to correctness (bins only get wider).
    constexpr long max_bins_per_direction = 1 << 16;
  } // namespace

  template <int dim>
  CellList<dim>::CellList(const Box<dim> &domain, const double width)
    : lower(domain.lower_corner())
    , length(domain.upper_corner() - domain.lower_corner())
    , period(domain.period())
  {
    Assert(width > 0, ExcInternalError());
    for (unsigned int d = 0; d < dim; ++d)
      n_bins[d] = std::clamp(static_cast<long>(std::floor(length[d] / width)), 1L,
                             max_bins_per_direction);
  }

  template <int dim>
  long CellList<dim>::row_of(const double x, const unsigned int d) const
  {
    // Clamped to a few periods: far outside the box every row is reached anyway, and the
    // cast to long stays defined.
    const double row = std::floor((x - lower[d]) / length[d] * n_bins[d]);
    return static_cast<long>(std::clamp(row, -2.0 * n_bins[d], 3.0 * n_bins[d]));
  }

  template <int dim>
  typename CellList<dim>::Bin CellList<dim>::bin_of(const Point<dim> &x) const
  {
    Bin b;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const long r = row_of(x[d], d);
        b[d] = wraps(d) ? wrap_row(r, d) : std::clamp(r, 0L, n_bins[d] - 1);
      }
    return b;
  }

  template <int dim>
  void CellList<dim>::insert(const unsigned int k, const Point<dim> &x)
  {
    members[bin_of(x)].push_back(k);
  }

  template <int dim>
  Tensor<1, dim> CellList<dim>::offset(const Point<dim> &a, const Point<dim> &b) const
  {
    return Box<dim>::nearest_image(a - b, period);
  }

  template class CellList<2>;
  template class CellList<3>;
} // namespace fdparticle
