// Unit test of the MUMPS layer the cut-cell patch uses (include/fdparticle/solvers/mumps.h)
// on a small saddle-point matrix laid out like the patch's: velocity rows, multiplier rows
// paired with them by a mass-like block and no diagonal, pressure rows with a small
// penalty. The rows are split over the ranks.
//  - mumps::nested_dissection returns a permutation; with groups, each multiplier row comes
//    right after the velocity row it is grouped with.
//  - mumps::Factorization solves A x = b to round-off against a solution chosen first: LU
//    of all entries, LDLᵀ of the lower triangle of the symmetric matrix, LU of a
//    non-symmetric one (a convection-like velocity block), and LDLᵀ of that one's
//    symmetric part given as the cut-cell patch gives it (half of each off-diagonal entry
//    at its place in the lower triangle, a_ij and a_ji both there: MUMPS must sum them),
//    with and without the ordering, to 1e-10 (round-off leaves about 1e-12).
// test-ranks: 1 2

#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/mumps.h>

#include "unit_check.h"

#include <Epetra_CrsMatrix.h>
#include <Epetra_MpiComm.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  constexpr int n_u = 30, n_p = 10, n = 2 * n_u + n_p;

  /// The matrix, dense: [K Mᵀ Gᵀ; M 0 0; G 0 −εI], K tridiagonal (with `convection`
  /// a non-symmetric part), M tridiagonal and diagonally dominant, G a difference of two
  /// velocities per pressure row.
  std::vector<std::vector<double>> make_matrix(const double convection)
  {
    std::vector<std::vector<double>> A(n, std::vector<double>(n, 0.));
    for (int i = 0; i < n_u; ++i)
      {
        A[i][i]          = 2.5;
        A[n_u + i][i]    = 1.;
        A[i][n_u + i]    = 1.;
        if (i + 1 < n_u)
          {
            A[i][i + 1]             = -1. + convection;
            A[i + 1][i]             = -1. - convection;
            A[n_u + i][i + 1]       = 0.25;
            A[n_u + i + 1][i]       = 0.25;
            A[i + 1][n_u + i]       = 0.25;
            A[i][n_u + i + 1]       = 0.25;
          }
      }
    for (int k = 0; k < n_p; ++k)
      {
        const int p = 2 * n_u + k;
        A[p][3 * k] = A[3 * k][p] = 1.;
        A[p][3 * k + 1] = A[3 * k + 1][p] = -1.;
        A[p][p]                            = -1e-3;
      }
    return A;
  }

  /// The matrix with this rank's rows of an even split.
  Epetra_CrsMatrix make_epetra(const std::vector<std::vector<double>> &A, const Epetra_Map &map)
  {
    Epetra_CrsMatrix E(Copy, map, 0);
    for (int r = 0; r < map.NumMyElements(); ++r)
      {
        const int           row = map.GID(r);
        std::vector<int>    cols;
        std::vector<double> values;
        for (int j = 0; j < n; ++j)
          if (A[row][j] != 0.)
            {
              cols.push_back(j);
              values.push_back(A[row][j]);
            }
        E.InsertGlobalValues(row, cols.size(), values.data(), cols.data());
      }
    E.FillComplete();
    return E;
  }

  /// How a matrix is handed to MUMPS: all entries (LU), the lower triangle (LDLᵀ), or
  /// halves of all off-diagonal entries at their lower-triangle places (LDLᵀ of the
  /// symmetric part).
  enum class Entries
  {
    all,
    lower,
    halves
  };

  /// Solve S x = S x_exact through mumps::Factorization from this rank's rows of A, S = A
  /// or (with halves) its symmetric part; the largest error on rank 0.
  double solve_error(const std::vector<std::vector<double>> &A, const Epetra_Map &map,
                     const Entries entries, std::vector<int> ordering)
  {
    std::vector<int>    rows, columns;
    std::vector<double> values;
    for (int r = 0; r < map.NumMyElements(); ++r)
      for (int j = 0; j < n; ++j)
        {
          const int row = map.GID(r);
          if (A[row][j] == 0. || (entries == Entries::lower && j > row))
            continue;
          const bool half = entries == Entries::halves && j != row;
          rows.push_back(half ? std::max(row, j) : row);
          columns.push_back(half ? std::min(row, j) : j);
          values.push_back(half ? 0.5 * A[row][j] : A[row][j]);
        }
    mumps::Factorization factorization(MPI_COMM_WORLD, n, entries != Entries::all, rows,
                                       columns, values);
    AssertThrow(factorization.analyse(ordering, mumps::initial_workspace_percent) >= 0,
                ExcMessage("analysis failed"));
    AssertThrow(factorization.factor() >= 0, ExcMessage("factorization failed"));

    std::vector<double> x_exact(n), b(n, 0.);
    for (int i = 0; i < n; ++i)
      x_exact[i] = std::sin(1. + i);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        b[i] += (entries == Entries::halves ? 0.5 * (A[i][j] + A[j][i]) : A[i][j]) * x_exact[j];
    const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    if (!root)
      b.clear();
    AssertThrow(factorization.solve(b) >= 0, ExcMessage("solve failed"));
    double error = 0;
    if (root)
      for (int i = 0; i < n; ++i)
        error = std::max(error, std::abs(b[i] - x_exact[i]));
    return Utilities::MPI::max(error, MPI_COMM_WORLD);
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool     root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  Epetra_MpiComm comm(MPI_COMM_WORLD);
  // Rows split evenly over the ranks.
  const Epetra_Map map(n, 0, comm);

  const auto             A = make_matrix(0.);
  const Epetra_CrsMatrix E = make_epetra(A, map);

  // The ordering, plain and with each multiplier row grouped with its velocity row.
  std::vector<int> group(map.NumMyElements());
  for (int r = 0; r < map.NumMyElements(); ++r)
    {
      const int row = map.GID(r);
      group[r]      = row >= n_u && row < 2 * n_u ? row - n_u : row;
    }
  const std::vector<int> plain   = mumps::nested_dissection(E, MPI_COMM_WORLD);
  const std::vector<int> grouped = mumps::nested_dissection(E, MPI_COMM_WORLD, group);
  auto is_permutation = [](const std::vector<int> &perm_in) {
    std::vector<bool> seen(n, false);
    for (const int k : perm_in)
      {
        if (k < 1 || k > n || seen[k - 1])
          return false;
        seen[k - 1] = true;
      }
    return perm_in.size() == static_cast<std::size_t>(n);
  };
  if (root)
    {
      check(is_permutation(plain), "nested_dissection: a permutation of the rows");
      check(is_permutation(grouped), "nested_dissection with groups: a permutation");
      int apart = 0;
      for (int i = 0; i < n_u; ++i)
        apart += grouped[n_u + i] != grouped[i] + 1;
      check(apart == 0, "each multiplier row right after its velocity row",
            std::to_string(apart) + " of " + std::to_string(n_u) + " are not");
    }
  else
    check(plain.empty() && grouped.empty(), "nested_dissection: the ordering on rank 0 only");

  // The matrix's condition number is about 10⁴: round-off leaves errors near 1e-12.
  const double tolerance = 1e-10;
  for (const bool ordered : {false, true})
    {
      const std::string how = ordered ? " (METIS, grouped)" : " (MUMPS's ordering)";
      const std::vector<int> ordering = ordered ? grouped : std::vector<int>();
      double e = solve_error(A, map, Entries::all, ordering);
      check(e <= tolerance, "LU of the symmetric saddle-point matrix" + how, sci(e));
      e = solve_error(A, map, Entries::lower, ordering);
      check(e <= tolerance, "LDLT of its lower triangle" + how, sci(e));
      e = solve_error(make_matrix(0.4), map, Entries::all, ordering);
      check(e <= tolerance, "LU of a non-symmetric one" + how, sci(e));
      e = solve_error(make_matrix(0.4), map, Entries::halves, ordering);
      check(e <= tolerance, "LDLT of its symmetric part, given in halves" + how, sci(e));
    }
  return summary();
}
