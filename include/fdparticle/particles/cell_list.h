#ifndef fdparticle_particles_cell_list_h
#define fdparticle_particles_cell_list_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <fdparticle/base/box.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Numbered points sorted into the bins of a regular grid over the box, for neighbour
   * queries in O(1) per point: the box is cut into bins at least as wide as the largest
   * distance asked about, so every point within that distance of x lies in the bin of x
   * or in an adjacent one. In a periodic direction the bins wrap around and distances are
   * to the nearest periodic image. Used by PairSearch and RandomPacking.
   */
  template <int dim>
  class CellList
  {
  public:
    /// Bins at least 'width' wide (one bin across a direction shorter than that).
    CellList(const Box<dim> &domain, const double width);

    /// Put point number k, at x, into its bin.
    void insert(const unsigned int k, const Point<dim> &x);

    /// Call f(k) for every point k in the bin of x and in the adjacent bins, each once.
    template <typename Function>
    void for_each_near(const Point<dim> &x, const Function &f) const;

    /// Call f(k) for every point k in the bins that the box [lower, upper] reaches, each
    /// once; in a periodic direction a box reaching past a face wraps around.
    template <typename Function>
    void for_each_in_box(const Point<dim> &lower, const Point<dim> &upper,
                         const Function &f) const;

    /// a − b, to the nearest periodic image of b.
    Tensor<1, dim> offset(const Point<dim> &a, const Point<dim> &b) const;

  private:
    using Bin = std::array<long, dim>;
    /// The bin of x; in a periodic direction that of its image in the box.
    Bin bin_of(const Point<dim> &x) const;
    /// Index of the bin row of coordinate x in direction d, not wrapped or clamped.
    long row_of(const double x, const unsigned int d) const;
    /// Whether the bins wrap around in direction d.
    bool wraps(const unsigned int d) const { return period[d] > 0; }
    /// Row r of direction d brought into [0, n_bins[d]) (a periodic direction).
    long wrap_row(const long r, const unsigned int d) const
    {
      return ((r % n_bins[d]) + n_bins[d]) % n_bins[d];
    }
    /// Call f(k) for every point k in the bins whose row in each direction d is one of
    /// rows[d] (each row listed once).
    template <typename Function>
    void visit(const std::array<std::vector<long>, dim> &rows, const Function &f) const;

    Point<dim>                               lower;
    Tensor<1, dim>                           length;
    /// Box::period(): the box length in a periodic direction, 0 in the others.
    Tensor<1, dim>                           period;
    std::array<long, dim>                    n_bins{};
    std::map<Bin, std::vector<unsigned int>> members;
  };

  template <int dim>
  template <typename Function>
  void CellList<dim>::for_each_near(const Point<dim> &x, const Function &f) const
  {
    // The distinct neighbour bins in each direction (with few bins, wrapping around a
    // periodic direction would list one bin twice).
    const Bin                          own = bin_of(x);
    std::array<std::vector<long>, dim> near;
    for (unsigned int d = 0; d < dim; ++d)
      for (long o = -1; o <= 1; ++o)
        {
          const long b = wraps(d) ? wrap_row(own[d] + o, d) : own[d] + o;
          if (b < 0 || b >= n_bins[d])
            continue;
          if (std::find(near[d].begin(), near[d].end(), b) == near[d].end())
            near[d].push_back(b);
        }
    visit(near, f);
  }

  template <int dim>
  template <typename Function>
  void CellList<dim>::for_each_in_box(const Point<dim> &box_lower, const Point<dim> &box_upper,
                                      const Function &f) const
  {
    // The distinct bin rows the box reaches in each direction, sorted.
    std::array<std::vector<long>, dim> rows;
    double                             n_reached = 1;
    for (unsigned int d = 0; d < dim; ++d)
      {
        const long first = row_of(box_lower[d], d), last = row_of(box_upper[d], d);
        if (wraps(d))
          for (long r = first; r <= last && long(rows[d].size()) < n_bins[d]; ++r)
            rows[d].push_back(wrap_row(r, d));
        else
          for (long r = std::max(first, 0L); r <= std::min(last, n_bins[d] - 1); ++r)
            rows[d].push_back(r);
        std::sort(rows[d].begin(), rows[d].end());
        n_reached *= rows[d].size();
      }
    if (n_reached == 0)
      return;
    // A box over more bins than hold points (a coarse cell, small balls) visits the
    // occupied bins instead of the reached ones.
    if (n_reached > members.size())
      {
        for (const auto &[bin, points] : members)
          {
            bool inside = true;
            for (unsigned int d = 0; d < dim; ++d)
              inside = inside && std::binary_search(rows[d].begin(), rows[d].end(), bin[d]);
            if (inside)
              for (const unsigned int k : points)
                f(k);
          }
        return;
      }
    visit(rows, f);
  }

  template <int dim>
  template <typename Function>
  void CellList<dim>::visit(const std::array<std::vector<long>, dim> &rows,
                            const Function                           &f) const
  {
    std::array<std::size_t, dim> choice{};
    while (true)
      {
        Bin b;
        for (unsigned int d = 0; d < dim; ++d)
          b[d] = rows[d][choice[d]];
        const auto it = members.find(b);
        if (it != members.end())
          for (const unsigned int k : it->second)
            f(k);
        // Next bin, odometer style.
        unsigned int d = 0;
        while (d < dim && ++choice[d] == rows[d].size())
          choice[d++] = 0;
        if (d == dim)
          break;
      }
  }
} // namespace fdparticle

#endif
