#include <deal.II/base/exceptions.h>

#include <fdparticle/bordered_system.h>

namespace fdparticle
{
  void BorderedSystem::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    {
      prm.declare_entry("Linear solver", "Amesos_Mumps",
                        Patterns::Selection("Amesos_Mumps|Amesos_Klu"),
                        "Direct solver for the finite-element block: MUMPS (parallel) or KLU "
                        "(serial, gathers the matrix on one rank).");
    }
    prm.leave_subsection();
  }

  void BorderedSystem::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    solver_type = prm.get("Linear solver");
    prm.leave_subsection();
  }

  void BorderedSystem::reinit(const IndexSet &                         owned,
                              const IndexSet &                         relevant,
                              const TrilinosWrappers::SparsityPattern &sparsity,
                              const MPI_Comm                           comm,
                              const unsigned int                       m)
  {
    // The factorization refers to A's Epetra matrix: release it before A changes.
    direct.reset();
    A.reinit(sparsity);
    // Writable ghost entries: cells at a partition boundary add into DoFs owned by a
    // neighbour, and compress(add) ships them there.
    r_fe.reinit(owned, relevant, comm, /*vector_writable=*/true);
    B.assign(m, r_fe);
    C.assign(m, r_fe);
    D.setZero(m, m);
    r_p.setZero(m);
  }

  void BorderedSystem::zero(const bool with_matrix)
  {
    r_fe = 0;
    r_p.setZero();
    if (!with_matrix)
      return;
    direct.reset();
    A = 0;
    for (auto &b : B)
      b = 0;
    for (auto &c : C)
      c = 0;
    D.setZero();
  }

  double BorderedSystem::residual_norm() const
  {
    return std::sqrt(r_fe.norm_sqr() + r_p.squaredNorm());
  }

  void BorderedSystem::solve_newton_step(TrilinosWrappers::MPI::Vector &x, Eigen::VectorXd &y)
  {
    if (!direct)
      {
        direct = std::make_unique<TrilinosWrappers::SolverDirect>(
          control, TrilinosWrappers::SolverDirect::AdditionalData(false, solver_type));
        direct->initialize(A);
      }
    const unsigned int m = B.size();

    const MPI_Comm comm = r_fe.get_mpi_communicator();
    const IndexSet owned = r_fe.locally_owned_elements();
    TrilinosWrappers::MPI::Vector rhs(owned, comm);
    rhs.equ(-1.0, r_fe);
    x.reinit(owned, comm);
    direct->solve(x, rhs); // x = z0 = −A⁻¹ r_fe
    y.setZero(m);
    if (m == 0)
      return;

    std::vector<TrilinosWrappers::MPI::Vector> Z(m, x);
    Eigen::MatrixXd                            S = D;
    Eigen::VectorXd                            g = -r_p;
    for (unsigned int j = 0; j < m; ++j)
      direct->solve(Z[j], B[j]);
    for (unsigned int i = 0; i < m; ++i)
      {
        g[i] -= C[i] * x;
        for (unsigned int j = 0; j < m; ++j)
          S(i, j) -= C[i] * Z[j];
      }
    // Full pivoting: S is tiny, and for neutrally buoyant particles D = 0.
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(S);
    AssertThrow(lu.isInvertible(),
                ExcMessage("The particle block of the Newton system is singular: a particle is "
                           "not resolved by the mesh (too few cells inside it?)."));
    y = lu.solve(g);
    for (unsigned int j = 0; j < m; ++j)
      x.add(-y[j], Z[j]);
  }
} // namespace fdparticle
