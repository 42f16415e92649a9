// Unit test of the assembly terms (include/fdparticle/fem/assembly/): each term's Jacobian
// is the derivative of its residual.
//
// On one cell, at a random iterate (u, λ, p) and random particle velocities, the residual of
// the terms is differentiated by central differences in every local DoF and in every
// particle unknown, and compared with what the terms assemble as the cell matrix, the
// border columns B (∂ residual / ∂(V, ω)) and the border rows C (∂ particle integrals /
// ∂(u, λ)); the particle rows of ParticleEquations likewise with their block D. Every term
// is at most quadratic in the unknowns, so central differences are exact up to round-off.
// Two cells: one cut by the ball (fluid momentum, pairing, cut-cell penalties) and one
// inside it (fluid momentum, interior pressure, pairing); both angular-velocity closures;
// a ball, and a turned ellipse or ellipsoid (the torque balance with J = Q J_body Qᵀ).
// AssemblyScratch's iterate and shape functions, read from the scalar elements, are
// compared with the FESystem's.

#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/assembly/cut_cell_penalties.h>
#include <fdparticle/fem/assembly/fluid_momentum.h>
#include <fdparticle/fem/assembly/interior_pressure.h>
#include <fdparticle/fem/assembly/multiplier_pairing.h>
#include <fdparticle/fem/assembly/particle_equations.h>
#include <fdparticle/fem/introspection.h>
#include <fdparticle/particles/rigid_body.h>

#include "unit_check.h"

#include <algorithm>
#include <random>
#include <string>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  /// Step of the central differences: the terms are quadratic, so only round-off limits it.
  constexpr double fd_step = 1e-4;
  /// Agreement asked of difference quotient and assembled derivative, relative to the
  /// largest entry of the assembled block.
  constexpr double fd_tolerance = 1e-8;

  template <int dim>
  struct OneCell
  {
    /// The cell [0, 1]^dim with a ball of radius 0.45 at (0.6, 0.55[, 0.5]) (cut cell) or
    /// of radius 3 (the cell lies inside it); or, turned, an ellipse or ellipsoid of
    /// semi-axes about these (its inertia tensor not diagonal, its ω × Jω not zero).
    OneCell(const bool inside, const std::string &closure, const bool ellipsoid = false)
      : fe(Introspection<dim>::finite_element())
      , fv(mapping, fe, Introspection<dim>::cell_quadrature(),
           update_values | update_gradients | update_quadrature_points | update_JxW_values)
      , scalar_fv(mapping, fe.base_element(0), Introspection<dim>::cell_quadrature(),
                  update_values | update_gradients)
      , pressure_fv(mapping, fe.base_element(fe.n_base_elements() - 1),
                    Introspection<dim>::cell_quadrature(), update_values | update_gradients)
      , fluid_momentum(fluid)
      , interior_pressure(fluid)
      , pairing(fluid, particles)
      , penalties(fluid, particles)
      , equations(fluid, particles)
    {
      ParameterHandler prm;
      declare_all_parameters(prm);
      const std::string center = (dim == 2 ? "0.6, 0.55" : "0.6, 0.55, 0.5");
      // The box is large enough for a ball that holds the whole cell.
      const std::string corner = (dim == 2 ? "-4, -4" : "-4, -4, -4");
      const std::string far = (dim == 2 ? "5, 5" : "5, 5, 5");
      prm.parse_input_from_string(
        "set Dimension = " + std::to_string(dim) + "\nset Gravity = " +
        (dim == 2 ? "0.3, -9.8" : "0.3, -9.8, 0.2") + "\nsubsection Geometry\n  set Lower corner = " +
        corner + "\n  set Upper corner = " + far + "\n  set Subdivisions = " +
        (dim == 2 ? "9, 9" : "9, 9, 9") + "\nend\nsubsection Fluid\n  set Density = 1.3\n"
        "  set Viscosity = 0.07\nend\nsubsection Particles\n  set Particles = " + center + " : " +
        (!ellipsoid ? (inside ? "3" : "0.45") :
                    dim == 2 ? (inside ? "ellipse 3, 2.4, 35" : "ellipse 0.45, 0.3, 35") :
                               (inside ? "ellipsoid 3, 2.4, 2.7, 1, 2, 3, 35" :
                                         "ellipsoid 0.45, 0.3, 0.38, 1, 2, 3, 35")) +
        " : 2.5\n  set Angular velocity closure = " + closure +
        "\nend\nsubsection Multiplier\n  set Interior pressure penalty = 0.3\nend\n");
      Domain<dim> domain;
      domain.parse_parameters(prm);
      fluid.parse_parameters(prm);
      particles.parse_parameters(prm, domain);
      interior_pressure.parse_parameters(prm);
      interior_pressure.set_reference_point(Point<dim>());
      penalties.parse_parameters(prm);

      GridGenerator::hyper_cube(tria, 0, 1);
      fv.reinit(tria.begin_active());
      scalar_fv.reinit(tria.begin_active());
      pressure_fv.reinit(tria.begin_active());
      const unsigned int nq = fv.n_quadrature_points;
      owner.resize(nq);
      for (unsigned int q = 0; q < nq; ++q)
        owner[q] = particles[0].contains(fv.quadrature_point(q)) ? 0 : -1;
      kind = inside ? CellKind::inside : CellKind::cut;

      std::mt19937                           random(2024 + dim);
      std::uniform_real_distribution<double> uniform(-1, 1);
      coefficients.reinit(fe.n_dofs_per_cell());
      for (auto &x : coefficients)
        x = uniform(random);
      history.resize(nq);
      for (auto &h : history)
        for (unsigned int d = 0; d < dim; ++d)
          h[d] = uniform(random);
      unknowns = Eigen::VectorXd(particles.n_unknowns());
      for (Eigen::Index j = 0; j < unknowns.size(); ++j)
        unknowns[j] = uniform(random);
    }

    /// Run the terms over the cell at the local coefficients x and particle unknowns y.
    AssemblyCopy<dim> assemble(const Vector<double> &x, const Eigen::VectorXd &y,
                               const bool with_matrix)
    {
      particles.set_unknowns(y);
      const unsigned int   n = fe.n_dofs_per_cell(), nq = fv.n_quadrature_points;
      AssemblyScratch<dim> s(fe, c, alpha, viscous_pairing, with_matrix);
      AssemblyCopy<dim>    copy(n, particles.size());
      s.kind = kind;
      s.cut_particle = 0;
      s.has_particle = std::any_of(owner.begin(), owner.end(), [](int k) { return k >= 0; });
      typename CutCellQuadrature<dim>::CellRule rule;
      rule.kind  = kind;
      rule.owner = owner;
      s.particle_fraction =
        (kind == CellKind::cut ? rule.particle_fraction(fv.get_JxW_values()) : 0.0);
      // The iterate at the points, from the local coefficients (every shape function has
      // one field and one component).
      // AssemblyScratch evaluates from the scalar elements; here the FESystem's shape
      // functions give the same values independently.
      s.reinit(scalar_fv, pressure_fv, x, Vector<double>(n));
      std::vector<Tensor<1, dim>> u(nq), lambda(nq);
      std::vector<Tensor<2, dim>> grad_u(nq), grad_lambda(nq);
      std::vector<double>         p(nq);
      for (unsigned int q = 0; q < nq; ++q)
        for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int c_i = fe.system_to_component_index(i).first;
            const unsigned int d = c_i % dim;
            switch (Introspection<dim>::field(c_i))
              {
                case Introspection<dim>::Field::velocity:
                  u[q][d] += x[i] * fv.shape_value(i, q);
                  grad_u[q][d] += x[i] * fv.shape_grad(i, q);
                  break;
                case Introspection<dim>::Field::multiplier:
                  lambda[q][d] += x[i] * fv.shape_value(i, q);
                  grad_lambda[q][d] += x[i] * fv.shape_grad(i, q);
                  break;
                case Introspection<dim>::Field::pressure:
                  p[q] += x[i] * fv.shape_value(i, q);
                  break;
              }
          }
      for (unsigned int q = 0; q < nq; ++q)
        evaluation_mismatch =
          std::max({evaluation_mismatch, (s.u[q] - u[q]).norm(), (s.lambda[q] - lambda[q]).norm(),
                    (s.grad_u[q] - grad_u[q]).norm(), (s.grad_lambda[q] - grad_lambda[q]).norm(),
                    std::abs(s.p[q] - p[q]), s.u_history[q].norm()});
      s.u_history = history;
      // The ball is free: its border vectors are assembled.
      if (with_matrix)
        {
          copy.touching.push_back(0);
          copy.border_B[0].reinit(n, RigidBody<dim>::n_unknowns);
          copy.border_C[0].reinit(n, RigidBody<dim>::n_unknowns);
        }
      const std::vector<const AssemblyTerm<dim> *> terms{&fluid_momentum, &interior_pressure,
                                                         &pairing, &penalties};
      s.owners = owner;
      s.nearest_surfaces.assign(nq, 0);
      s.weights.resize(nq);
      for (unsigned int q = 0; q < nq; ++q)
        {
          s.q = q;
          s.JxW = s.weights[q] = fv.JxW(q);
          s.x = fv.quadrature_point(q);
          s.particle = owner[q];
          s.reinit_point(q);
          for (unsigned int i = 0; i < n; ++i)
            evaluation_mismatch =
              std::max({evaluation_mismatch, std::abs(s.N[i] - fv.shape_value(i, q)),
                        (s.dN[i] - fv.shape_grad(i, q)).norm()});
          for (const auto *term : terms)
            term->assemble_point(s, copy);
        }
      if (with_matrix)
        {
          for (const auto *term : terms)
            term->assemble_cell_matrix(s, copy);
        }
      return copy;
    }

    /// The particle residual r_p at the integrals of x and the unknowns y.
    Eigen::VectorXd particle_residual(const Vector<double> &x, const Eigen::VectorXd &y)
    {
      const AssemblyCopy<dim> copy = assemble(x, y, false);
      NewtonSystem            system;
      system.r_p = Eigen::VectorXd::Zero(y.size());
      system.D.resize(y.size(), y.size());
      equations.assemble(copy.integrals, c, false, system);
      return system.r_p;
    }

    const std::array<double, 3> c{{1.5 / 0.05, -2 / 0.05, 0.5 / 0.05}}; // BDF2, Δt = 0.05
    const double                alpha = 1.3 * 1.5 / 0.05;
    /// c μ of the pairing weight κ = α + c μ/R² (c = 10, the default, at the fluid's
    /// μ = 1): κ ≠ α in every term.
    const double                viscous_pairing = 10;
    Fluid<dim>                  fluid;
    ParticleSet<dim>            particles;
    FESystem<dim>               fe;
    MappingQ<dim>               mapping{1};
    Triangulation<dim>          tria;
    FEValues<dim>               fv;
    /// The same points for the scalar elements of (u, λ) and of p (AssemblyScratch::reinit).
    FEValues<dim>               scalar_fv, pressure_fv;
    /// Largest difference between AssemblyScratch's iterate and shape functions at the
    /// points and the FESystem's.
    double                      evaluation_mismatch = 0;
    FluidMomentum<dim>          fluid_momentum;
    InteriorPressure<dim>       interior_pressure;
    MultiplierPairing<dim>      pairing;
    CutCellPenalties<dim>       penalties;
    ParticleEquations<dim>      equations;
    CellKind                    kind;
    std::vector<int>            owner;
    Vector<double>              coefficients;
    std::vector<Tensor<1, dim>> history;
    Eigen::VectorXd             unknowns;
  };

  /// Worst |difference quotient − assembled| over a block, and the block's largest entry.
  struct Mismatch
  {
    double worst = 0, scale = 0;
    void   add(const double quotient, const double assembled)
    {
      worst = std::max(worst, std::abs(quotient - assembled));
      scale = std::max(scale, std::abs(assembled));
    }
    void report(const std::string &what) const
    {
      check(scale > 0 && worst <= fd_tolerance * scale, what,
            "worst difference " + std::to_string(worst) + " of largest entry " +
              std::to_string(scale));
    }
  };

  template <int dim>
  void check_cell(const bool inside, const std::string &closure, const bool ellipsoid = false)
  {
    OneCell<dim>       cell(inside, closure, ellipsoid);
    const unsigned int n = cell.fe.n_dofs_per_cell();
    const unsigned int m = cell.unknowns.size();
    const auto         at = cell.assemble(cell.coefficients, cell.unknowns, true);
    const std::string  name = std::to_string(dim) + "D " + (inside ? "inside" : "cut") +
                             (ellipsoid ? (dim == 2 ? " (ellipse)" : " (ellipsoid)") : "") +
                             " cell, " + closure + ": ";
    std::cout << name << std::count(cell.owner.begin(), cell.owner.end(), 0) << " of "
              << cell.owner.size() << " points in the ball" << std::endl;
    // The coefficients are O(1): round-off of a few sums of products.
    check(cell.evaluation_mismatch <= 1e-12, name + "iterate and shape functions from the scalar elements",
          "largest difference " + std::to_string(cell.evaluation_mismatch));

    // The particle integrals entering the rows C: <λ, e_i>, <λ, e_j × r> or −½ ∫ curl u.
    const auto particle_rows = [&](const AssemblyCopy<dim> &copy) {
      std::vector<double> rows(m);
      const auto         &I = copy.integrals[0];
      for (unsigned int d = 0; d < dim; ++d)
        rows[d] = I.lambda_force[d];
      for (unsigned int j = 0; j < RigidBody<dim>::n_rotations; ++j)
        rows[dim + j] = (closure == "torque balance" ? I.lambda_torque * RigidBody<dim>::rotation_axis(j) :
                                                       -0.5 * (I.curl_u * RigidBody<dim>::rotation_axis(j)));
      return rows;
    };

    Mismatch matrix, rows;
    for (unsigned int j = 0; j < n; ++j)
      {
        Vector<double> plus = cell.coefficients, minus = cell.coefficients;
        plus[j] += fd_step;
        minus[j] -= fd_step;
        const auto up = cell.assemble(plus, cell.unknowns, false);
        const auto down = cell.assemble(minus, cell.unknowns, false);
        for (unsigned int i = 0; i < n; ++i)
          matrix.add((up.rhs[i] - down.rhs[i]) / (2 * fd_step), at.matrix(i, j));
        const auto r_up = particle_rows(up), r_down = particle_rows(down);
        for (unsigned int k = 0; k < m; ++k)
          rows.add((r_up[k] - r_down[k]) / (2 * fd_step), at.border_C[0](j, k));
      }
    matrix.report(name + "cell matrix = d(cell residual)/d(u, lambda, p)");
    rows.report(name + "border rows C = d(particle integrals)/d(u, lambda)");

    Mismatch columns, block;
    const Eigen::VectorXd r_p = cell.particle_residual(cell.coefficients, cell.unknowns);
    NewtonSystem          system;
    system.r_p = Eigen::VectorXd::Zero(m);
    system.D.resize(m, m);
    cell.equations.assemble(at.integrals, cell.c, true, system);
    for (unsigned int k = 0; k < m; ++k)
      {
        Eigen::VectorXd plus = cell.unknowns, minus = cell.unknowns;
        plus[k] += fd_step;
        minus[k] -= fd_step;
        const auto up = cell.assemble(cell.coefficients, plus, false);
        const auto down = cell.assemble(cell.coefficients, minus, false);
        for (unsigned int i = 0; i < n; ++i)
          columns.add((up.rhs[i] - down.rhs[i]) / (2 * fd_step), at.border_B[0](i, k));
        // D from the particle rows alone (their dependence on λ and u is C).
        const Eigen::VectorXd d_r =
          (cell.particle_residual(cell.coefficients, plus) -
           cell.particle_residual(cell.coefficients, minus)) / (2 * fd_step);
        for (unsigned int i = 0; i < m; ++i)
          block.add(d_r[i], system.D.coeff(i, k));
      }
    columns.report(name + "border columns B = d(cell residual)/d(V, omega)");
    block.report(name + "particle block D = d(particle rows)/d(V, omega)");
    check(std::abs(system.r_p.norm() - r_p.norm()) <= 1e-12 * r_p.norm(),
          name + "the particle rows do not depend on with_matrix");
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const std::string closure : {"torque balance", "kinematic"})
    for (const bool inside : {false, true})
      {
        check_cell<2>(inside, closure);
        check_cell<3>(inside, closure);
        check_cell<2>(inside, closure, true);
        check_cell<3>(inside, closure, true);
      }
  return summary();
}
