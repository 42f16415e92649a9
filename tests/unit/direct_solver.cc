// Unit test of fdparticle::DirectSolver (include/fdparticle/solvers/direct_solver.h) on a
// NewtonSystem (include/fdparticle/solvers/newton_system.h): the
// Newton correction, from the Schur complement of the particle block (few particle
// unknowns) or from the factorization of the whole bordered matrix (many), must equal the
// solution of the bordered system solved densely (Eigen, full-pivot LU), for every direct
// solver and MUMPS ordering the parameter file can select.
//
// The finite-element block is a small saddle-point matrix like the real one: an
// unsymmetric "velocity" block (convection-diffusion stencil) and "pressure" rows that
// couple to velocity only, with no diagonal entry (so the solver has to pivot off the
// diagonal). The bookkeeping of the factorization is checked too: a system laid out again
// with the same pattern keeps the symbolic factorization, new values need a new numeric
// one, and a new pattern needs a new symbolic one. Linear solver = auto chooses by size.

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <fdparticle/solvers/direct_solver.h>
#include <fdparticle/solvers/linear_solver_factory.h>
#include <fdparticle/solvers/newton_system.h>

#include "unit_check.h"

#include <Eigen/Dense>

#include <cmath>
#include <string>
#include <vector>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  constexpr unsigned int n_u = 40, n_p = 19, n = n_u + n_p;
  /// Particle unknowns: 3 (the Schur complement) and 20 (the bordered matrix K), on either
  /// side of DirectSolver's max_schur_unknowns.
  unsigned int m = 0;

  /// Pressure row k couples to the velocities k and k + 1 (a discrete divergence).
  TrilinosWrappers::SparsityPattern make_pattern(const bool extra_entry)
  {
    const IndexSet                    all = complete_index_set(n);
    TrilinosWrappers::SparsityPattern sp(all, all, MPI_COMM_WORLD);
    for (unsigned int i = 0; i < n_u; ++i)
      for (unsigned int j = (i > 0 ? i - 1 : 0); j <= std::min(i + 1, n_u - 1); ++j)
        sp.add(i, j);
    for (unsigned int k = 0; k < n_p; ++k)
      {
        sp.add(n_u + k, k);
        sp.add(n_u + k, k + 1);
        sp.add(k, n_u + k);
        sp.add(k + 1, n_u + k);
      }
    if (extra_entry)
      sp.add(0, n_u - 1);
    sp.compress();
    return sp;
  }

  /// Lay the system out as the program does each step: the solver hears of a new pattern
  /// before A changes.
  void lay_out(NewtonSystem &s, DirectSolver &solver, const bool extra_entry)
  {
    const IndexSet                          all     = complete_index_set(n);
    const TrilinosWrappers::SparsityPattern pattern = make_pattern(extra_entry);
    const bool                              new_pattern = !s.has_pattern(pattern);
    if (new_pattern)
      solver.pattern_changed();
    // B and C couple the particle unknowns to the velocities.
    TrilinosWrappers::SparsityPattern border = NewtonSystem::border_pattern(all, all, m, MPI_COMM_WORLD);
    if (m > 0)
      {
        for (unsigned int i = 0; i < n_u; ++i)
          for (unsigned int j = 0; j < m; ++j)
            border.add(i, j);
        border.compress();
      }
    s.reinit(all, all, pattern, new_pattern, border, MPI_COMM_WORLD);
  }

  /// Fill A, B, C, D and the residuals; 'shift' changes the values, not the pattern.
  Eigen::MatrixXd fill(NewtonSystem &s, DirectSolver &solver, const double shift,
                       const bool extra_entry)
  {
    s.zero(true);
    solver.operator_changed();
    Eigen::MatrixXd full = Eigen::MatrixXd::Zero(n + m, n + m);
    auto set = [&](const unsigned int i, const unsigned int j, const double v) {
      s.A.set(i, j, v);
      full(i, j) = v;
    };
    for (unsigned int i = 0; i < n_u; ++i)
      {
        set(i, i, 2.5 + shift + 0.01 * i);
        if (i > 0)
          set(i, i - 1, -1.3);
        if (i + 1 < n_u)
          set(i, i + 1, -0.7);
      }
    for (unsigned int k = 0; k < n_p; ++k)
      {
        set(n_u + k, k, 1.0);
        set(n_u + k, k + 1, -1.0 - 0.1 * shift);
        set(k, n_u + k, -1.0);
        set(k + 1, n_u + k, 1.0);
      }
    if (extra_entry)
      set(0, n_u - 1, 0.05);
    s.A.compress(VectorOperation::insert);
    for (unsigned int j = 0; j < m; ++j)
      for (unsigned int i = 0; i < n_u; ++i)
        {
          const double b = std::sin(1.0 + i + 7.0 * j), c = std::cos(2.0 + 3.0 * i + j);
          s.B.set(i, j, b);
          s.C_transposed.set(i, j, c);
          full(i, n + j) = b;
          full(n + j, i) = c;
        }
    if (m > 0)
      s.compress_border(VectorOperation::insert);
    for (unsigned int i = 0; i < n; ++i)
      s.r_fe[i] = std::sin(0.3 * i) + shift;
    s.r_fe.compress(VectorOperation::insert);
    for (unsigned int i = 0; i < m; ++i)
      {
        s.r_p[i] = 0.5 - i;
        for (unsigned int j = 0; j < m; ++j)
          full(n + i, n + j) = s.D.coeffRef(i, j) = (i == j ? 4.0 : 0.3);
      }
    return full;
  }

  /// Max-norm difference between DirectSolver::solve() and the dense solution.
  double error(NewtonSystem &s, DirectSolver &solver, const Eigen::MatrixXd &full)
  {
    Eigen::VectorXd rhs(n + m);
    for (unsigned int i = 0; i < n; ++i)
      rhs[i] = -s.r_fe[i];
    rhs.tail(m) = -s.r_p;
    const Eigen::VectorXd exact = full.fullPivLu().solve(rhs);

    TrilinosWrappers::MPI::Vector x;
    Eigen::VectorXd               y;
    const auto info = solver.solve(s, 1e-12, x, y);
    check(info.iterations == 1 && info.residual == 0, "a direct solve reports one exact step");
    double e = 0;
    for (unsigned int i = 0; i < n; ++i)
      e = std::max(e, std::abs(x[i] - exact[i]));
    for (unsigned int i = 0; i < m; ++i)
      e = std::max(e, std::abs(y[i] - exact[n + i]));
    return e / exact.lpNorm<Eigen::Infinity>();
  }

  void check_solver(const std::string &solver_name, const std::string &ordering)
  {
    const std::string what = solver_name +
                             (solver_name == "Amesos_Mumps" ? " (" + ordering + ")" : "") +
                             ", m = " + std::to_string(m);
    ParameterHandler prm;
    declare_linear_solver_parameters(prm);
    prm.parse_input_from_string("subsection Solver\n"
                                "  set Linear solver = direct\n"
                                "  set Direct solver = " + solver_name + "\n"
                                "  set MUMPS ordering = " + ordering + "\n"
                                "end\n");
    NewtonSystem s; // declared first: the solver refers to its matrix until destroyed
    const std::unique_ptr<LinearSolver> created = create_linear_solver(prm, 2, n + m);
    auto *solver = dynamic_cast<DirectSolver *>(created.get());
    check(solver != nullptr, what + ": 'Linear solver' selects the direct solver");
    if (!solver)
      return;

    lay_out(s, *solver, false);
    Eigen::MatrixXd full = fill(s, *solver, 0.0, false);
    check(error(s, *solver, full) < 1e-12, what + ": Newton step equals the dense solution");
    // Same pattern again (as after a time step in which no constraint changed).
    lay_out(s, *solver, false);
    full = fill(s, *solver, 0.7, false);
    check(error(s, *solver, full) < 1e-12, what + ": new values, same pattern");
    const auto &st = solver->statistics();
    check(st.n_symbolic == 1 && st.n_numeric == 2,
          what + ": the same pattern keeps the symbolic factorization",
          std::to_string(st.n_symbolic) + " symbolic, " + std::to_string(st.n_numeric) +
            " numeric");
    // A second solve with the same operator reuses the numeric factorization.
    check(error(s, *solver, full) < 1e-12 && st.n_numeric == 2,
          what + ": a second solve reuses the numeric factorization");
    // A new pattern: a new symbolic factorization.
    lay_out(s, *solver, true);
    full = fill(s, *solver, 0.2, true);
    check(error(s, *solver, full) < 1e-12 && st.n_symbolic == 2,
          what + ": a new pattern gets a new symbolic factorization");
  }

  /// Linear solver = auto: the iterative solver from 'Iterative solver from' unknowns on.
  void check_auto_choice()
  {
    ParameterHandler prm;
    declare_linear_solver_parameters(prm);
    prm.parse_input_from_string("subsection Solver\n"
                                "  set Linear solver = auto\n"
                                "  set Iterative solver from = 1000\n"
                                "end\n");
    check(!create_linear_solver(prm, 2, 999)->iterative(), "auto: 999 unknowns go to the direct solver");
    check(create_linear_solver(prm, 2, 1000)->iterative(),
          "auto: 1000 unknowns go to the iterative solver");
  }

  /// MUMPS ordering = default: METIS nested dissection in 3D, QAMD in 2D.
  void check_default_ordering()
  {
    ParameterHandler prm;
    declare_linear_solver_parameters(prm);
    for (const unsigned int dim : {2u, 3u})
      {
        const std::unique_ptr<LinearSolver> created = create_linear_solver(prm, dim, 100);
        const auto *solver = dynamic_cast<const DirectSolver *>(created.get());
        const std::string expected = dim == 3 ? "metis" : "qamd";
        check(solver != nullptr && solver->ordering() == expected,
              "default ordering in " + std::to_string(dim) + "D is " + expected);
      }
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const unsigned int particle_unknowns : {3u, 20u})
    {
      m = particle_unknowns;
      for (const std::string ordering : {"auto", "amd", "amf", "qamd", "pord", "metis"})
        check_solver("Amesos_Mumps", ordering);
      check_solver("Amesos_Klu", "auto");
    }
  check_auto_choice();
  check_default_ordering();
  return summary();
}
