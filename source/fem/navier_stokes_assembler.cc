#include <deal.II/base/mpi.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <fdparticle/fem/navier_stokes_assembler.h>
#include <fdparticle/core/parameter_tools.h>
#include <fdparticle/particles/rigid_body.h>

namespace fdparticle
{
  namespace
  {
    /// Which field a shape function of the (u, λ, p) system belongs to.
    enum Field
    {
      velocity = 0,
      multiplier = 1,
      pressure = 2
    };

    /// FEValues for the rule of a cell: the two fixed rules are reused, a rule made for
    /// this cell alone (level set) gets its own object.
    template <int dim>
    FEValues<dim> &fe_values_for(const typename CutCellQuadrature<dim>::CellRule &rule,
                                 FEValues<dim> &regular, FEValues<dim> &cut,
                                 std::unique_ptr<FEValues<dim>> &cell_specific)
    {
      if (rule.quadrature == &rule.cell_specific)
        {
          cell_specific = std::make_unique<FEValues<dim>>(regular.get_mapping(), regular.get_fe(),
                                                          rule.cell_specific,
                                                          regular.get_update_flags());
          return *cell_specific;
        }
      return rule.kind == CellKind::cut ? cut : regular;
    }

    /// Particle fraction θ of a cut cell: its quadrature weights inside a particle over all.
    template <int dim>
    double particle_fraction_of(const FEValues<dim> &                            fv,
                                const typename CutCellQuadrature<dim>::CellRule &rule)
    {
      double inside = 0, total = 0;
      for (unsigned int q = 0; q < fv.n_quadrature_points; ++q)
        {
          total += fv.JxW(q);
          inside += (rule.owner[q] >= 0 ? fv.JxW(q) : 0.0);
        }
      return inside / total;
    }
  } // namespace

  template <int dim>
  void NavierStokesAssembler<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    {
      prm.declare_entry("Fluid penalty", "0.01", Patterns::Anything(),
                        "s >= 0 in the term s*alpha^2/(alpha + mu/R^2)*int(lambda.eta) over the fluid part of cut "
                        "cells (the seed's weak lambda = 0 in the fluid, 3.18a). It keeps the "
                        "rows of multipliers that barely meet a particle well posed.");
      prm.declare_entry("Strain penalty", "0.15", Patterns::Anything(),
                        "s_e >= 0 in the term s_e*mu*int(2 eps(lambda):eps(eta)) over the fluid "
                        "part of cut cells. It softens the rigidity constraint of multipliers "
                        "that lie mostly in the fluid (0: the cut cells lock, the particle acts "
                        "O(h) too large) without touching the rigid modes of lambda, which "
                        "carry force and torque (doc/method.md, 'Strain penalty').");
      prm.declare_entry("Penalty ramp", "0.2", Patterns::Anything(),
                        "theta_0 >= 0: in a cut cell whose particle fraction theta is below "
                        "theta_0, both penalties above are scaled by theta/theta_0, so they "
                        "switch on continuously as a cell starts to be cut (smoother particle "
                        "velocities, doc/smoothness.md). 0: off, the penalties switch on at "
                        "full strength (then Strain penalty = 0.05 was the accurate choice, "
                        "doc/method.md §4).");
      prm.declare_entry("Pairing time step", "0", Patterns::Anything(),
                        "dt_p >= 0. 0: the pairing <lambda, v> = int(alpha lambda.v + mu "
                        "grad lambda : grad v) uses alpha = 3 rho/(2 dt) of the current step "
                        "(the seed, doc/method.md §0). dt_p > 0: alpha = 3 rho/(2 dt_p) in the "
                        "pairing and in the fluid penalty, whatever dt is. Any pairing gives "
                        "the same continuous problem, but the discrete rigidity constraint "
                        "and its penalties then no longer change with dt, so a time-step "
                        "study sees the scheme's own order (BDF2: 2) and a step halved by "
                        "recovery solves the same discrete constraint (doc/method.md §4).");
      prm.declare_entry("Interior pressure penalty", "1e-3", Patterns::Anything(),
                        "delta >= 0 in the term -(delta/mu)*int((p - p_hydrostatic) q) over cells "
                        "inside a particle. Inside a rigid body p and lambda are determined only "
                        "together (p + phi, lambda + psi with <psi, v> = int phi div v solve the "
                        "same equations, up to the multiplier penalties); this picks the "
                        "hydrostatic pressure there. It switches on as a cell becomes inside, "
                        "so keep it small: delta = 1 made the particle velocity step by 5e-4 at "
                        "every such event, 1e-3 removes the steps, 1e-6 is too weak for "
                        "round-off (doc/method.md §4).");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void NavierStokesAssembler<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Multiplier");
    const auto get = [&](const std::string &name) {
      return ParameterTools::get_non_negative(prm, name, "Multiplier/" + name);
    };
    fluid_penalty = get("Fluid penalty");
    strain_penalty = get("Strain penalty");
    penalty_ramp = get("Penalty ramp");
    pairing_time_step = get("Pairing time step");
    interior_pressure_penalty = get("Interior pressure penalty");
    prm.leave_subsection();
  }

  template <int dim>
  NavierStokesAssembler<dim>::NavierStokesAssembler(const FESystem<dim> &         fe,
                                                    const Fluid<dim> &            fluid,
                                                    const ParticleSet<dim> &      particles,
                                                    const CutCellQuadrature<dim> &quadrature)
    : fe(fe)
    , fluid(fluid)
    , particles(particles)
    , quadrature(quadrature)
  {}

  template <int dim>
  std::vector<ParticleIntegrals<dim>> NavierStokesAssembler<dim>::assemble(
    const DoFHandler<dim> &dof_handler, const TrilinosWrappers::MPI::Vector &solution,
    const TrilinosWrappers::MPI::Vector &history, const std::array<double, 3> &c,
    const AffineConstraints<double> &constraints, const bool with_matrix,
    NewtonSystem &system) const
  {
    using RB = RigidBody<dim>;
    const FEValuesExtractors::Vector vel(0), lam(dim);
    const FEValuesExtractors::Scalar pres(2 * dim);
    const UpdateFlags flags =
      update_values | update_gradients | update_quadrature_points | update_JxW_values;
    FEValues<dim> fe_regular(mapping, fe, quadrature.regular_rule(), flags);
    FEValues<dim> fe_cut(mapping, fe, quadrature.cut_rule(), flags);
    std::unique_ptr<FEValues<dim>> fe_cell_specific;

    // Every shape function is primitive: one field, one vector component.
    const unsigned int        n = fe.n_dofs_per_cell();
    std::vector<unsigned int> comp(n);
    std::vector<unsigned int> dofs[3];
    for (unsigned int i = 0; i < n; ++i)
      {
        const unsigned int c_i = fe.system_to_component_index(i).first;
        comp[i] = c_i % dim;
        dofs[c_i < dim ? velocity : (c_i < 2 * dim ? multiplier : pressure)].push_back(i);
      }
    const auto &u_dofs = dofs[velocity];
    const auto &l_dofs = dofs[multiplier];
    const auto &p_dofs = dofs[pressure];

    const double         rho = fluid.density, mu = fluid.viscosity;
    // α of the pairing <λ, v> (doc/method.md §0); the fluid's own ρ c0 u stays in the momentum rows.
    const double alpha = (pairing_time_step > 0 ? 1.5 * rho / pairing_time_step : rho * c[0]);
    const Tensor<1, dim> static_force = fluid.hydrostatic_gradient(); // ρ g + f
    const unsigned int   n_rot = RB::n_rotations;

    system.zero(with_matrix);
    std::vector<ParticleIntegrals<dim>> integrals(particles.size());

    FullMatrix<double>                   cell_matrix(n, n);
    Vector<double>                       cell_rhs(n);
    std::vector<types::global_dof_index> dof_indices(n);
    // Border vectors of each particle met in the cell: [particle][unknown] → local vector.
    std::vector<std::vector<Vector<double>>> local_B(particles.size()), local_C(particles.size());
    std::vector<int>                         touching;
    std::vector<double>                      N(n);
    std::vector<Tensor<1, dim>>              dN(n);

    typename CutCellQuadrature<dim>::CellRule rule;
    std::vector<Tensor<1, dim>>               u, uh, l;
    std::vector<Tensor<2, dim>>               gu, gl;
    std::vector<double>                       p;

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        quadrature.reinit(cell, particles, rule);
        FEValues<dim> &fv = fe_values_for<dim>(rule, fe_regular, fe_cut, fe_cell_specific);
        fv.reinit(cell);
        quadrature.assign_owners(fv.get_quadrature_points(), particles, rule);
        const unsigned int nq = fv.n_quadrature_points;
        u.resize(nq), uh.resize(nq), l.resize(nq), gu.resize(nq), gl.resize(nq), p.resize(nq);
        fv[vel].get_function_values(solution, u);
        fv[vel].get_function_gradients(solution, gu);
        fv[vel].get_function_values(history, uh);
        fv[pres].get_function_values(solution, p);
        const bool has_particle =
          std::any_of(rule.owner.begin(), rule.owner.end(), [](int k) { return k >= 0; });
        const bool penalise =
          (rule.kind == CellKind::cut && (fluid_penalty > 0 || strain_penalty > 0));
        // Optional ramp of the penalties with the cell's particle fraction θ (Penalty ramp):
        // without it they switch on at full strength when a cell starts to be cut.
        const double ramp = (penalise && penalty_ramp > 0 ?
                               std::min(1.0, particle_fraction_of(fv, rule) / penalty_ramp) :
                               1.0);
        if (has_particle || penalise)
          {
            fv[lam].get_function_values(solution, l);
            fv[lam].get_function_gradients(solution, gl);
          }

        cell_rhs = 0;
        if (with_matrix)
          cell_matrix = 0;
        touching.clear();
        for (const int k : rule.owner)
          if (k >= 0 && std::find(touching.begin(), touching.end(), k) == touching.end())
            {
              touching.push_back(k);
              if (with_matrix && particles[k].first_unknown != numbers::invalid_unsigned_int)
                {
                  local_B[k].assign(RB::n_unknowns, Vector<double>(n));
                  local_C[k].assign(RB::n_unknowns, Vector<double>(n));
                }
            }

        for (unsigned int q = 0; q < nq; ++q)
          {
            const double JxW = fv.JxW(q);
            const int    k = rule.owner[q];
            for (unsigned int i = 0; i < n; ++i)
              {
                N[i] = fv.shape_value(i, q);
                dN[i] = fv.shape_grad(i, q);
              }

            // 1.–2. Fluid momentum and continuity on the whole box.
            const Tensor<1, dim> convection =
              (fluid.convection ? gu[q] * u[q] : Tensor<1, dim>());
            const Tensor<1, dim> m_force = rho * (c[0] * u[q] + uh[q] + convection) - static_force;
            const Tensor<2, dim> two_mu_eps = mu * (gu[q] + transpose(gu[q]));
            const double         div_u = trace(gu[q]);
            for (const unsigned int i : u_dofs)
              cell_rhs(i) += (m_force[comp[i]] * N[i] + two_mu_eps[comp[i]] * dN[i] -
                              p[q] * dN[i][comp[i]]) *
                             JxW;
            for (const unsigned int i : p_dofs)
              cell_rhs(i) -= N[i] * div_u * JxW;
            if (rule.kind == CellKind::inside && interior_pressure_penalty > 0)
              {
                // Fix the pressure/multiplier null mode inside rigid bodies (see parameter).
                // The sign makes it the stabilising −C block of the symmetric saddle point
                // [[A, Bᵀ], [B, −C]] (B = −(q, ∇·v)); where the mode is not exact the other
                // sign would destabilise.
                const double eps = -interior_pressure_penalty / mu * JxW;
                const double p_static = static_force * (fv.quadrature_point(q) - pressure_reference);
                for (const unsigned int i : p_dofs)
                  {
                    cell_rhs(i) += eps * (p[q] - p_static) * N[i];
                    if (with_matrix)
                      for (const unsigned int j : p_dofs)
                        cell_matrix(i, j) += eps * N[i] * N[j];
                  }
              }
            if (with_matrix)
              for (const unsigned int i : u_dofs)
                {
                  const unsigned int ci = comp[i];
                  for (const unsigned int j : u_dofs)
                    {
                      const unsigned int cj = comp[j];
                      // 2μ ε(φ_j):ε(φ_i) = μ (δ ∇N_i·∇N_j + ∂_cj N_i ∂_ci N_j)
                      double value = mu * dN[i][cj] * dN[j][ci];
                      if (ci == cj)
                        value += rho * c[0] * N[i] * N[j] + mu * (dN[i] * dN[j]) +
                                 (fluid.convection ? rho * N[i] * (dN[j] * u[q]) : 0.0);
                      if (fluid.convection)
                        value += rho * N[i] * gu[q][ci][cj] * N[j];
                      cell_matrix(i, j) += value * JxW;
                    }
                  for (const unsigned int j : p_dofs)
                    {
                      const double b = -N[j] * dN[i][ci] * JxW;
                      cell_matrix(i, j) += b;
                      cell_matrix(j, i) += b;
                    }
                }

            if (k >= 0)
              {
                // 3. Rigidity in P_k, and the −<λ, v> term of the momentum equation.
                const Particle<dim> &P = particles[k];
                const Tensor<1, dim> r = fv.quadrature_point(q) - P.geometry_center;
                const Tensor<1, dim> du = u[q] - P.velocity - RB::cross(P.omega, r);
                const Tensor<2, dim> dgu = gu[q] - RB::rotation_gradient(P.omega);
                for (const unsigned int i : u_dofs)
                  cell_rhs(i) -= (alpha * l[q][comp[i]] * N[i] + mu * (gl[q][comp[i]] * dN[i])) * JxW;
                for (const unsigned int a : l_dofs)
                  cell_rhs(a) += (alpha * du[comp[a]] * N[a] + mu * (dgu[comp[a]] * dN[a])) * JxW;

                ParticleIntegrals<dim> &I = integrals[k];
                I.lambda_force += alpha * l[q] * JxW;
                for (unsigned int j = 0; j < 3; ++j)
                  {
                    Tensor<1, 3> e;
                    e[j] = 1;
                    I.lambda_torque[j] += (alpha * (l[q] * RB::cross(e, r)) +
                                           mu * scalar_product(gl[q], RB::rotation_gradient(e))) *
                                          JxW;
                  }
                I.curl_u += RB::curl(gu[q]) * JxW;
                I.volume += JxW;

                if (with_matrix)
                  {
                    for (const unsigned int a : l_dofs)
                      for (const unsigned int b : u_dofs)
                        if (comp[a] == comp[b])
                          {
                            const double m = (alpha * N[a] * N[b] + mu * (dN[a] * dN[b])) * JxW;
                            cell_matrix(a, b) += m;
                            cell_matrix(b, a) -= m;
                          }
                    if (P.first_unknown != numbers::invalid_unsigned_int)
                      {
                        // Border: ∂(rigidity)/∂(V, ω) and ∂(particle rows)/∂(λ or u).
                        for (const unsigned int a : l_dofs)
                          {
                            const unsigned int ca = comp[a];
                            local_B[k][ca](a) -= alpha * N[a] * JxW;
                            local_C[k][ca](a) += alpha * N[a] * JxW;
                            for (unsigned int j = 0; j < n_rot; ++j)
                              {
                                const Tensor<1, 3>   e = RB::rotation_axis(j);
                                const double pairing =
                                  (alpha * N[a] * RB::cross(e, r)[ca] +
                                   mu * (RB::rotation_gradient(e)[ca] * dN[a])) *
                                  JxW;
                                local_B[k][dim + j](a) -= pairing;
                                if (particles.closure() == AngularVelocityClosure::torque_balance)
                                  local_C[k][dim + j](a) += pairing;
                              }
                          }
                        if (particles.closure() == AngularVelocityClosure::kinematic)
                          for (const unsigned int b : u_dofs)
                            {
                              Tensor<2, dim> G;
                              G[comp[b]] = dN[b];
                              const Tensor<1, 3> curl = RB::curl(G);
                              for (unsigned int j = 0; j < n_rot; ++j)
                                local_C[k][dim + j](b) -= 0.5 * (curl * RB::rotation_axis(j)) * JxW;
                            }
                      }
                  }
              }
            else if (penalise)
              {
                // Weak λ = 0 on the fluid part of a cut cell (seed 3.18a), weighted by
                // α²/(α + μ/R²). The rigid mode of λ carries the particle's force through
                // α∫λ, so it grows like 1/α; a weight that does not vanish like α² for
                // α ≪ μ/R² lets the particle leak in proportion to Δt (weight α + μ/R²:
                // settling 10x too fast at Δt = 1). For α ≫ μ/R² the weight is sα, a fixed
                // fraction of the pairing (doc/method.md, "Fluid penalty").
                const double R = particles[rule.particle].radius;
                const double s =
                  ramp * fluid_penalty * alpha * alpha / (alpha + mu / (R * R)) * JxW;
                // Strain penalty s_e μ (2ε(λ), ε(η)): softens the rigidity of λ DoFs that live
                // mostly in the fluid (without it the cut cells lock, the particle looks
                // O(h) larger) and is blind to λ's rigid modes, ε(V + θ × r) = 0. Only in
                // cells that own particle points: elsewhere those rigid modes would be held
                // by the vanishing α² term alone (doc/method.md §4, "Strain penalty").
                const double se = (has_particle ? ramp * strain_penalty * mu * JxW : 0.0);
                for (const unsigned int a : l_dofs)
                  {
                    const unsigned int ca = comp[a];
                    cell_rhs(a) += s * l[q][ca] * N[a];
                    if (se != 0)
                      for (unsigned int j = 0; j < dim; ++j)
                        cell_rhs(a) += se * (gl[q][ca][j] + gl[q][j][ca]) * dN[a][j];
                    if (with_matrix)
                      for (const unsigned int b : l_dofs)
                        {
                          const unsigned int cb = comp[b];
                          double value = se * dN[a][cb] * dN[b][ca];
                          if (ca == cb)
                            value += s * N[a] * N[b] + se * (dN[a] * dN[b]);
                          cell_matrix(a, b) += value;
                        }
                  }
              }
          }

        cell->get_dof_indices(dof_indices);
        if (with_matrix)
          {
            constraints.distribute_local_to_global(cell_matrix, cell_rhs, dof_indices, system.A,
                                                   system.r_fe);
            for (const int k : touching)
              if (particles[k].first_unknown != numbers::invalid_unsigned_int)
                for (unsigned int j = 0; j < RB::n_unknowns; ++j)
                  {
                    constraints.distribute_local_to_global(local_B[k][j], dof_indices,
                                                           system.B[particles[k].first_unknown + j]);
                    constraints.distribute_local_to_global(local_C[k][j], dof_indices,
                                                           system.C[particles[k].first_unknown + j]);
                  }
          }
        else
          constraints.distribute_local_to_global(cell_rhs, dof_indices, system.r_fe);
      }

    system.r_fe.compress(VectorOperation::add);
    if (with_matrix)
      {
        system.A.compress(VectorOperation::add);
        for (auto &b : system.B)
          b.compress(VectorOperation::add);
        for (auto &cc : system.C)
          cc.compress(VectorOperation::add);
      }

    // Sum the particle integrals over all ranks.
    const MPI_Comm      comm = dof_handler.get_communicator();
    std::vector<double> packed;
    for (const auto &I : integrals)
      {
        for (unsigned int d = 0; d < dim; ++d)
          packed.push_back(I.lambda_force[d]);
        for (unsigned int d = 0; d < 3; ++d)
          packed.push_back(I.lambda_torque[d]);
        for (unsigned int d = 0; d < 3; ++d)
          packed.push_back(I.curl_u[d]);
        packed.push_back(I.volume);
      }
    Utilities::MPI::sum(packed, comm, packed);
    unsigned int pos = 0;
    for (auto &I : integrals)
      {
        for (unsigned int d = 0; d < dim; ++d)
          I.lambda_force[d] = packed[pos++];
        for (unsigned int d = 0; d < 3; ++d)
          I.lambda_torque[d] = packed[pos++];
        for (unsigned int d = 0; d < 3; ++d)
          I.curl_u[d] = packed[pos++];
        I.volume = packed[pos++];
      }

    // 4.–5. Particle rows, from the integrals.
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const Particle<dim> &P = particles[k];
        if (P.first_unknown == numbers::invalid_unsigned_int)
          continue;
        const unsigned int     f = P.first_unknown;
        const double           drho = P.density - rho;
        const Tensor<1, dim>   dVdt = c[0] * P.velocity + c[1] * P.velocity_old + c[2] * P.velocity_old2;
        const Tensor<1, 3>     dwdt = c[0] * P.omega + c[1] * P.omega_old + c[2] * P.omega_old2;
        for (unsigned int d = 0; d < dim; ++d)
          {
            system.r_p[f + d] =
              drho * P.volume() * (dVdt[d] - fluid.gravity[d]) + integrals[k].lambda_force[d];
            if (with_matrix)
              system.D(f + d, f + d) = drho * P.volume() * c[0];
          }
        for (unsigned int j = 0; j < n_rot; ++j)
          {
            const Tensor<1, 3> e = RB::rotation_axis(j);
            if (particles.closure() == AngularVelocityClosure::torque_balance)
              {
                system.r_p[f + dim + j] =
                  drho * P.inertia() * (dwdt * e) + integrals[k].lambda_torque * e;
                if (with_matrix)
                  system.D(f + dim + j, f + dim + j) = drho * P.inertia() * c[0];
              }
            else
              {
                system.r_p[f + dim + j] =
                  integrals[k].volume * (P.omega * e) - 0.5 * (integrals[k].curl_u * e);
                if (with_matrix)
                  system.D(f + dim + j, f + dim + j) = integrals[k].volume;
              }
          }
      }
    return integrals;
  }

  template <int dim>
  typename NavierStokesAssembler<dim>::ParticleSupport
  NavierStokesAssembler<dim>::particle_support(const DoFHandler<dim> &         dof_handler,
                                               const IndexSet &                 locally_relevant,
                                               const AffineConstraints<double> &mesh_constraints) const
  {
    bool any_inside = false;
    // The λ DoFs of the cells a particle meets, and the masters of those among them that
    // hanging nodes or periodicity tie to other DoFs: λ lives in the conforming space, whose
    // basis function of a master includes its slaves' pieces, so the master's support meets
    // the particle too. Without the masters, a constrained λ on a cut cell would be tied to
    // a λ = 0 of the fluid (and which of two periodic DoFs is the master depends on the
    // partition, so the results would depend on the number of ranks).
    std::vector<types::global_dof_index> marked;
    FEValues<dim> fe_regular(mapping, fe, quadrature.regular_rule(), update_quadrature_points);
    FEValues<dim> fe_cut(mapping, fe, quadrature.cut_rule(), update_quadrature_points);
    std::unique_ptr<FEValues<dim>>            fe_cell_specific;
    typename CutCellQuadrature<dim>::CellRule rule;
    std::vector<types::global_dof_index>      dof_indices(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        quadrature.reinit(cell, particles, rule);
        if (rule.kind == CellKind::fluid)
          continue;
        any_inside = any_inside || (rule.kind == CellKind::inside);
        if (rule.kind == CellKind::cut)
          {
            FEValues<dim> &fv = fe_values_for<dim>(rule, fe_regular, fe_cut, fe_cell_specific);
            fv.reinit(cell);
            quadrature.assign_owners(fv.get_quadrature_points(), particles, rule);
            if (std::none_of(rule.owner.begin(), rule.owner.end(), [](int k) { return k >= 0; }))
              continue;
          }
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < dof_indices.size(); ++i)
          {
            const unsigned int c_i = fe.system_to_component_index(i).first;
            if (c_i < dim || c_i >= 2 * dim)
              continue;
            marked.push_back(dof_indices[i]);
            if (const auto *line = mesh_constraints.get_constraint_entries(dof_indices[i]))
              for (const auto &entry : *line)
                marked.push_back(entry.first);
          }
      }
    // Masters may lie outside the locally relevant DoFs: they are ghosts of the marker.
    IndexSet ghosts = locally_relevant;
    {
      IndexSet masters(dof_handler.n_dofs());
      std::sort(marked.begin(), marked.end());
      marked.erase(std::unique(marked.begin(), marked.end()), marked.end());
      masters.add_indices(marked.begin(), marked.end());
      ghosts.add_indices(masters);
    }
    LinearAlgebra::distributed::Vector<double> marker(dof_handler.locally_owned_dofs(), ghosts,
                                                      dof_handler.get_communicator());
    for (const auto i : marked)
      marker[i] = 1;
    marker.compress(VectorOperation::max);
    marker.update_ghost_values();
    ParticleSupport support;
    support.active_multipliers.set_size(dof_handler.n_dofs());
    for (const auto i : locally_relevant)
      if (marker[i] > 0)
        support.active_multipliers.add_index(i);
    support.active_multipliers.compress();
    support.pressure_level_fixed =
      interior_pressure_penalty > 0 &&
      Utilities::MPI::logical_or(any_inside, dof_handler.get_communicator());
    return support;
  }

  template <int dim>
  Vector<float> NavierStokesAssembler<dim>::particle_fraction(const DoFHandler<dim> &dof_handler) const
  {
    Vector<float> fraction(dof_handler.get_triangulation().n_active_cells());
    const UpdateFlags flags = update_quadrature_points | update_JxW_values;
    FEValues<dim> fe_regular(mapping, fe, quadrature.regular_rule(), flags);
    FEValues<dim> fe_cut(mapping, fe, quadrature.cut_rule(), flags);
    std::unique_ptr<FEValues<dim>>            fe_cell_specific;
    typename CutCellQuadrature<dim>::CellRule rule;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        quadrature.reinit(cell, particles, rule);
        if (rule.kind == CellKind::inside)
          fraction[cell->active_cell_index()] = 1;
        else if (rule.kind == CellKind::cut)
          {
            FEValues<dim> &fv = fe_values_for<dim>(rule, fe_regular, fe_cut, fe_cell_specific);
            fv.reinit(cell);
            quadrature.assign_owners(fv.get_quadrature_points(), particles, rule);
            fraction[cell->active_cell_index()] = particle_fraction_of(fv, rule);
          }
      }
    return fraction;
  }

  template class NavierStokesAssembler<2>;
  template class NavierStokesAssembler<3>;
} // namespace fdparticle
