#include <fdparticle/particles/pair_search.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace fdparticle
{
  namespace
  {
    /// Bins per direction at most: keeps the bin keys small when the reach is tiny
    /// against the box, at no cost to correctness (bins only get wider).
    constexpr long max_bins_per_direction = 1 << 16;
  } // namespace

  template <int dim>
  PairSearch<dim>::PairSearch(const Domain<dim> &domain)
    : lower(domain.lower_corner())
    , length(domain.upper_corner() - domain.lower_corner())
  {
    for (unsigned int d = 0; d < dim; ++d)
      periodic[d] = domain.is_periodic(d);
  }

  template <int dim>
  std::vector<typename PairSearch<dim>::Pair>
  PairSearch<dim>::pairs(const std::vector<Point<dim>> &x, const std::vector<double> &r,
                         const double reach) const
  {
    AssertDimension(x.size(), r.size());
    std::vector<Pair> result;
    if (x.size() < 2)
      return result;
    // Two balls within reach have centres closer than this; a bin is at least as wide.
    const double cutoff = 2 * *std::max_element(r.begin(), r.end()) + std::max(reach, 0.0);
    std::array<long, dim> n_bins;
    for (unsigned int d = 0; d < dim; ++d)
      n_bins[d] = std::clamp(static_cast<long>(std::floor(length[d] / cutoff)), 1L,
                             max_bins_per_direction);

    using Bin = std::array<long, dim>;
    std::vector<Bin>                          bin_of(x.size());
    std::map<Bin, std::vector<unsigned int>> members;
    for (unsigned int k = 0; k < x.size(); ++k)
      {
        for (unsigned int d = 0; d < dim; ++d)
          bin_of[k][d] = std::clamp(static_cast<long>(std::floor((x[k][d] - lower[d]) /
                                                                  length[d] * n_bins[d])),
                                    0L, n_bins[d] - 1);
        members[bin_of[k]].push_back(k);
      }

    for (unsigned int i = 0; i < x.size(); ++i)
      {
        // The distinct neighbour bins in each direction (with few bins, wrapping around
        // a periodic direction would list one bin twice).
        std::array<std::vector<long>, dim> near;
        for (unsigned int d = 0; d < dim; ++d)
          {
            for (long o = -1; o <= 1; ++o)
              {
                long b = bin_of[i][d] + o;
                if (periodic[d])
                  b = (b + n_bins[d]) % n_bins[d];
                else if (b < 0 || b >= n_bins[d])
                  continue;
                if (std::find(near[d].begin(), near[d].end(), b) == near[d].end())
                  near[d].push_back(b);
              }
          }
        std::array<std::size_t, dim> choice{};
        while (true)
          {
            Bin b;
            for (unsigned int d = 0; d < dim; ++d)
              b[d] = near[d][choice[d]];
            const auto it = members.find(b);
            if (it != members.end())
              for (const unsigned int j : it->second)
                if (j > i)
                  {
                    Tensor<1, dim> offset = x[i] - x[j];
                    for (unsigned int d = 0; d < dim; ++d)
                      if (periodic[d])
                        offset[d] -= length[d] * std::round(offset[d] / length[d]);
                    const double gap = offset.norm() - r[i] - r[j];
                    if (gap < reach)
                      result.push_back(Pair{i, j, offset, gap});
                  }
            // Next combination of neighbour bins, odometer style.
            unsigned int d = 0;
            while (d < dim && ++choice[d] == near[d].size())
              choice[d++] = 0;
            if (d == dim)
              break;
          }
      }
    return result;
  }

  template class PairSearch<2>;
  template class PairSearch<3>;
} // namespace fdparticle
