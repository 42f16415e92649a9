#ifndef fdparticle_tests_unit_check_h
#define fdparticle_tests_unit_check_h

// The checks every unit test prints and counts: one line per check, "ok" or "FAIL" with the
// value found and the value expected; summary() is the program's exit code.

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <algorithm>
#include <limits>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

namespace unit_check
{
  inline unsigned int n_checks = 0, n_failed = 0;

  inline void check(const bool ok, const std::string &what, const std::string &detail = "")
  {
    ++n_checks;
    if (!ok)
      ++n_failed;
    std::cout << (ok ? "  ok    " : "  FAIL  ") << what;
    if (!ok && !detail.empty())
      std::cout << "  [" << detail << "]";
    std::cout << std::endl;
  }

  inline void check_close(const double value, const double expected, const double tol,
                          const std::string &what)
  {
    std::ostringstream s;
    s.precision(17);
    s << "got " << value << ", expected " << expected << ", tol " << tol;
    check(std::abs(value - expected) <= tol, what, s.str());
  }

  template <int rank, int dim>
  void check_close(const dealii::Tensor<rank, dim> &value,
                   const dealii::Tensor<rank, dim> &expected, const double tol,
                   const std::string &what)
  {
    std::ostringstream s;
    s.precision(17);
    s << "got " << value << ", expected " << expected << ", tol " << tol;
    check((value - expected).norm() <= tol, what, s.str());
  }

  /// A number in short scientific notation, for messages.
  inline std::string sci(const double x)
  {
    std::ostringstream s;
    s << std::scientific << std::setprecision(2) << x;
    return s.str();
  }

  /// Parameter text of a scene in the unit box [0,1]^dim with N cells a direction, no gravity.
  template <int dim>
  std::string unit_box_parameters(const unsigned int N)
  {
    const std::string zero = (dim == 2 ? "0, 0" : "0, 0, 0");
    const std::string one = (dim == 2 ? "1, 1" : "1, 1, 1");
    std::string       n = std::to_string(N) + ", " + std::to_string(N);
    if (dim == 3)
      n += ", " + std::to_string(N);
    return "set Dimension = " + std::to_string(dim) + "\nset Gravity = " + zero +
           "\nsubsection Geometry\n  set Lower corner = " + zero + "\n  set Upper corner = " + one +
           "\n  set Subdivisions = " + n + "\nend\n";
  }

  /**
   * a − b to the nearest periodic image of b, found by brute force: every shift by −1, 0
   * or +1 box lengths in the periodic directions of the domain (a fdparticle::Domain).
   * The reference the neighbour searches are checked against.
   */
  template <int dim, typename Domain>
  dealii::Tensor<1, dim> nearest_image_offset(const dealii::Point<dim> &a,
                                              const dealii::Point<dim> &b, const Domain &domain)
  {
    const dealii::Tensor<1, dim> length = domain.upper_corner() - domain.lower_corner();
    dealii::Tensor<1, dim>       best   = a - b;
    for (unsigned int s = 0; s < std::pow(3, dim); ++s)
      {
        dealii::Tensor<1, dim> offset = a - b;
        unsigned int           code = s;
        bool                   allowed = true;
        for (unsigned int d = 0; d < dim; ++d, code /= 3)
          {
            const int shift = int(code % 3) - 1;
            allowed = allowed && (shift == 0 || domain.is_periodic(d));
            offset[d] += shift * length[d];
          }
        if (allowed && offset.norm() < best.norm())
          best = offset;
      }
    return best;
  }

  /// |a − b| to the nearest periodic image of b (nearest_image_offset).
  template <int dim, typename Domain>
  double nearest_image_distance(const dealii::Point<dim> &a, const dealii::Point<dim> &b,
                                const Domain &domain)
  {
    return nearest_image_offset(a, b, domain).norm();
  }

  /// Print the tally; 0 if every check passed (use as main's return value).
  inline int summary()
  {
    std::cout << (n_failed == 0 ? "PASSED" : "FAILED") << ": " << n_checks - n_failed << " of "
              << n_checks << " checks" << std::endl;
    return n_failed == 0 ? 0 : 1;
  }
} // namespace unit_check

#endif
