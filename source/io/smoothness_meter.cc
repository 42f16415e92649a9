#include <fdparticle/io/smoothness_meter.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <istream>
#include <ostream>

namespace fdparticle
{
  template <int dim>
  void SmoothnessMeter<dim>::record(const ParticleSet<dim> &particles)
  {
    history.resize(particles.size());
    for (unsigned int k = 0; k < particles.size(); ++k)
      history[k].push_back(particles[k].velocity);
  }

  template <int dim>
  double SmoothnessMeter<dim>::smoothness(const unsigned int k) const
  {
    const auto &        V = history[k];
    const std::size_t   N = V.size();
    const std::size_t   skip = std::max<std::size_t>(3, N / 10);
    double              first = 0, second = 0;
    std::size_t         n1 = 0, n2 = 0;
    for (std::size_t n = skip + 1; n < N; ++n)
      {
        first += V[n].norm_square();
        ++n1;
        if (n + 1 < N)
          {
            second += (V[n + 1] - 2 * V[n] + V[n - 1]).norm_square();
            ++n2;
          }
      }
    if (n2 == 0 || first == 0)
      return 0;
    return std::sqrt(second / n2) / std::sqrt(first / n1);
  }

  template <int dim>
  void SmoothnessMeter<dim>::write(const std::string &directory, ConditionalOStream &pcout,
                                   const bool root) const
  {
    for (unsigned int k = 0; k < history.size(); ++k)
      pcout << "particle " << k << ": smoothness S = " << std::setprecision(4) << smoothness(k)
            << " (RMS of the second difference of V / RMS of V, doc/method.md)" << std::endl;
    if (!root)
      return;
    std::ofstream out(directory + "/smoothness.csv");
    out << "id,smoothness,samples\n" << std::setprecision(10);
    for (unsigned int k = 0; k < history.size(); ++k)
      out << k << ',' << smoothness(k) << ',' << history[k].size() << '\n';
  }

  template <int dim>
  void SmoothnessMeter<dim>::save(std::ostream &out) const
  {
    out << std::setprecision(17) << history.size() << '\n';
    for (const auto &h : history)
      {
        out << h.size();
        for (const auto &v : h)
          for (unsigned int d = 0; d < dim; ++d)
            out << ' ' << v[d];
        out << '\n';
      }
  }

  template <int dim>
  void SmoothnessMeter<dim>::load(std::istream &in)
  {
    std::size_t n = 0;
    in >> n;
    history.assign(n, {});
    for (auto &h : history)
      {
        std::size_t m = 0;
        in >> m;
        h.resize(m);
        for (auto &v : h)
          for (unsigned int d = 0; d < dim; ++d)
            in >> v[d];
      }
  }

  template class SmoothnessMeter<2>;
  template class SmoothnessMeter<3>;
} // namespace fdparticle
