// Unit test of fdparticle::NewtonSolver (include/fdparticle/solvers/newton_solver.h), driven
// through its callbacks on small problems whose solutions and Newton iterates are known by
// hand:
//  - the circle x² + y² = 4 cut by the line x = y: root (√2, √2), quadratic convergence;
//  - a linear 2×2 system: one correction, the exact solution;
//  - log(x) = 1 from x = 10: the full step lands at x < 0 (NaN) and only the line search
//    reaches the root e;
//  - x² = 0: Newton converges only linearly (halving), so an iteration limit is hit;
//  - a correction of the wrong sign and length: the residual grows a thousandfold a step;
//  - a linear solve that throws, and a residual that is NaN from the start.
// Each failure must end with its own reason and a message, never with "converged".

#include <fdparticle/solvers/newton_solver.h>

#include "unit_check.h"

#include <Eigen/Dense>

#include <cmath>
#include <vector>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

using namespace fdparticle;
using namespace unit_check;

namespace
{
  using Outcome = NewtonSolver::Outcome;

  /// A problem F(x) = 0 in R^n with its Jacobian, and the bookkeeping NewtonSolver::Problem
  /// asks of a caller: the state, the state before the last correction, the correction.
  struct TestProblem
  {
    std::function<Eigen::VectorXd(const Eigen::VectorXd &)> F;
    std::function<Eigen::MatrixXd(const Eigen::VectorXd &)> J;
    Eigen::VectorXd x, x0, dx, residual;
    Eigen::MatrixXd jacobian;
    unsigned int    n_jacobians = 0, n_residuals = 0;
    /// The relative tolerance each linear solve was given.
    std::vector<double> tolerances;
    bool            solve_throws = false;

    NewtonSolver::Problem callbacks(const bool linear = false)
    {
      NewtonSolver::Problem p;
      p.assemble = [this](const bool with_jacobian) {
        residual = F(x);
        ++n_residuals;
        if (with_jacobian)
          {
            jacobian = J(x);
            ++n_jacobians;
          }
        return residual.norm();
      };
      p.solve = [this](const double relative_tolerance) {
        if (solve_throws)
          throw std::runtime_error("the factorization broke down");
        tolerances.push_back(relative_tolerance);
        x0 = x;
        dx = jacobian.fullPivLu().solve(-residual);
        return 1u;
      };
      p.apply_update = [this](const double theta) { x = x0 + theta * dx; };
      p.describe_residual = [this]() { return "x = " + std::to_string(x[0]); };
      p.linear = linear;
      return p;
    }
  };

  NewtonSolver solver(const bool line_search, const bool reuse, const unsigned int max_iterations = 20)
  {
    NewtonSolver s;
    s.tolerance      = 1e-12;
    s.line_search    = line_search;
    s.reuse_jacobian = reuse;
    s.max_iterations = max_iterations;
    return s;
  }

  TestProblem circle()
  {
    TestProblem p;
    p.F = [](const Eigen::VectorXd &v) {
      return Eigen::Vector2d(v[0] * v[0] + v[1] * v[1] - 4, v[0] - v[1]).eval();
    };
    p.J = [](const Eigen::VectorXd &v) {
      Eigen::MatrixXd j(2, 2);
      j << 2 * v[0], 2 * v[1], 1, -1;
      return j;
    };
    p.x = Eigen::Vector2d(3, 1);
    return p;
  }

  TestProblem scalar(std::function<double(double)> f, std::function<double(double)> df,
                     const double start)
  {
    TestProblem p;
    p.F = [f](const Eigen::VectorXd &v) { return Eigen::VectorXd::Constant(1, f(v[0])); };
    p.J = [df](const Eigen::VectorXd &v) { return Eigen::MatrixXd::Constant(1, 1, df(v[0])); };
    p.x = Eigen::VectorXd::Constant(1, start);
    return p;
  }

  void expect_failure(const NewtonSolver::Result &r, const Outcome expected, const std::string &what,
                      const std::string &phrase)
  {
    check(r.outcome == expected, what + ": the reason is reported",
          "outcome " + std::to_string(int(r.outcome)) + ", message '" + r.message + "'");
    check(!r.converged() && r.message.find(phrase) != std::string::npos,
          what + ": not converged, the message says '" + phrase + "'", r.message);
  }
} // namespace

int main()
{
  // Quadratic convergence to (√2, √2); exact Newton assembles a Jacobian every iteration.
  {
    TestProblem p      = circle();
    const auto  result = solver(true, false).solve(p.callbacks());
    check(result.converged(), "circle: converged", result.message);
    check_close(p.x[0], std::sqrt(2.0), 1e-12, "circle: x = sqrt 2");
    check_close(p.x[1], std::sqrt(2.0), 1e-12, "circle: y = sqrt 2");
    check(result.iterations >= 4 && result.iterations <= 7,
          "circle: Newton needs 4-7 iterations from (3, 1)", std::to_string(result.iterations));
    check(p.n_jacobians == result.iterations,
          "exact Newton: one Jacobian per iteration (the last one converges)",
          std::to_string(p.n_jacobians) + " Jacobians, " + std::to_string(result.iterations) +
            " iterations");
    check(result.residual <= 1e-12 * result.initial_residual && result.residual == p.residual.norm(),
          "circle: the reported residual is the final one, below the relative tolerance");

    // Inexact Newton: the forcing terms (the relative tolerances given to the linear
    // solves) start at 0.1, tighten as the residual falls, and never ask for more than
    // half of what reaching the target still needs.
    const auto &eta = p.tolerances;
    check(eta.size() == result.iterations && !eta.empty() && eta[0] == 0.1,
          "circle: forcing term 0.1 on the first iteration", std::to_string(eta.front()));
    check(eta.back() < 1e-3 && eta.back() < eta[1],
          "circle: the forcing term tightens as Newton converges", std::to_string(eta.back()));
    bool bounded = true;
    for (const double e : eta)
      bounded = bounded && e <= 0.1 && e > 0;
    check(bounded, "circle: forcing terms in (0, 0.1]");

    // Modified Newton: the same root with fewer Jacobians than iterations.
    TestProblem q        = circle();
    const auto  modified = solver(true, true).solve(q.callbacks());
    check(modified.converged() && std::abs(q.x[0] - std::sqrt(2.0)) < 1e-12,
          "circle, Jacobian reused: converged to the root");
    check(q.n_jacobians < modified.iterations,
          "circle, Jacobian reused: fewer Jacobians than iterations",
          std::to_string(q.n_jacobians) + " Jacobians, " + std::to_string(modified.iterations) +
            " iterations");
  }

  // A linear problem: one correction, the full step, the exact solution.
  {
    TestProblem p;
    Eigen::MatrixXd A(2, 2);
    A << 4, 1, 2, 3;
    const Eigen::Vector2d b(1, 2);
    p.F                = [A, b](const Eigen::VectorXd &v) { return (A * v - b).eval(); };
    p.J                = [A](const Eigen::VectorXd &) { return A; };
    p.x                = Eigen::Vector2d(0, 0);
    const auto result  = solver(true, true).solve(p.callbacks(true));
    const Eigen::Vector2d exact(0.1, 0.6);
    check(result.converged() && result.iterations == 1, "linear: one correction");
    check((p.x - exact).norm() < 1e-14, "linear: the exact solution (0.1, 0.6)");
    check(p.n_residuals == 2, "linear: no line search (two residual assemblies)",
          std::to_string(p.n_residuals));
    // One solve to half the target: tolerance 1e-12 · max(1, |R_0|) relative to |R_0|.
    const double r0 = b.norm();
    check(p.tolerances.size() == 1 && std::abs(p.tolerances[0] - 0.5e-12 * std::max(1.0, r0) / r0) < 1e-20,
          "linear: the one solve is converged to half the Newton target",
          p.tolerances.empty() ? "none" : std::to_string(p.tolerances[0]));
  }

  // A linear problem with a small cubic term, as a contact force adds to a Stokes step:
  // the first exact correction leaves the residual above the target, and Newton goes on
  // until it is met (once, one correction was accepted as converged).
  {
    TestProblem p;
    Eigen::MatrixXd A(2, 2);
    A << 4, 1, 2, 3;
    const Eigen::Vector2d b(1, 2);
    p.F = [A, b](const Eigen::VectorXd &v) {
      Eigen::VectorXd r = A * v - b;
      r[0] += 10 * v[0] * v[0] * v[0];
      return r;
    };
    p.J = [A](const Eigen::VectorXd &v) {
      Eigen::MatrixXd j = A;
      j(0, 0) += 30 * v[0] * v[0];
      return j;
    };
    p.x               = Eigen::Vector2d(0, 0);
    const auto result = solver(true, true).solve(p.callbacks(true));
    check(result.converged() && p.F(p.x).norm() <= 1e-12 * b.norm(),
          "linear with a cubic term: converged to the target",
          "residual " + sci(p.F(p.x).norm()) + " after " + std::to_string(result.iterations) +
            " corrections");
    check(result.iterations > 1, "linear with a cubic term: more than one correction",
          std::to_string(result.iterations) + " corrections");
  }

  // log x = 1 from x = 10: the full Newton step goes to x = 10 − 10·log 10 < 0.
  {
    auto make = []() {
      return scalar([](double x) { return std::log(x) - 1; }, [](double x) { return 1 / x; }, 10);
    };
    TestProblem p      = make();
    const auto  result = solver(true, false).solve(p.callbacks());
    check(result.converged() && std::abs(p.x[0] - std::exp(1.0)) < 1e-12,
          "log x = 1: the line search reaches x = e");
    TestProblem q = make();
    expect_failure(solver(false, false).solve(q.callbacks()), Outcome::not_finite,
                   "log x = 1 without line search", "not finite");
  }

  // x² = 0 halves x each iteration: 1e-12 is out of reach in 5 iterations.
  {
    TestProblem p = scalar([](double x) { return x * x; }, [](double x) { return 2 * x; }, 1);
    const auto  result = solver(true, false, 5).solve(p.callbacks());
    expect_failure(result, Outcome::too_many_iterations, "x^2 = 0", "did not converge in 5");
    check(result.iterations == 5 && std::abs(p.x[0] - 1.0 / 32) < 1e-15,
          "x^2 = 0: five halvings were made");
  }

  // A correction of the wrong sign (Jacobian −1e-3 for F = x − 1): the residual grows.
  {
    TestProblem p = scalar([](double x) { return x - 1; }, [](double) { return -1e-3; }, 2);
    expect_failure(solver(false, true).solve(p.callbacks()), Outcome::diverged, "wrong Jacobian",
                   "Newton diverges");
  }

  // A linear solve that throws.
  {
    TestProblem p  = circle();
    p.solve_throws = true;
    expect_failure(solver(true, true).solve(p.callbacks()), Outcome::linear_solver_failed,
                   "throwing linear solve", "the factorization broke down");
  }

  // NaN from the start must not count as converged (a NaN target would accept anything).
  {
    TestProblem p = scalar([](double) { return std::numeric_limits<double>::quiet_NaN(); },
                           [](double) { return 1.0; }, 1);
    expect_failure(solver(true, true).solve(p.callbacks()), Outcome::not_finite,
                   "NaN initial residual", "not finite");
  }

  return summary();
}
