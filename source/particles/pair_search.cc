#include <fdparticle/particles/cell_list.h>
#include <fdparticle/particles/pair_search.h>

#include <algorithm>

namespace fdparticle
{
  template <int dim>
  PairSearch<dim>::PairSearch(const Box<dim> &domain)
    : domain(domain)
  {}

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
    const double  cutoff = 2 * *std::max_element(r.begin(), r.end()) + std::max(reach, 0.0);
    CellList<dim> list(domain, cutoff);
    for (unsigned int k = 0; k < x.size(); ++k)
      list.insert(k, x[k]);
    for (unsigned int i = 0; i < x.size(); ++i)
      list.for_each_near(x[i], [&](const unsigned int j) {
        if (j > i)
          {
            const Tensor<1, dim> offset = list.offset(x[i], x[j]);
            const double         gap = offset.norm() - r[i] - r[j];
            if (gap < reach)
              result.push_back(Pair{i, j, offset, gap});
          }
      });
    return result;
  }

  template class PairSearch<2>;
  template class PairSearch<3>;
} // namespace fdparticle
