#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <fdparticle/solvers/direct_solver.h>
#include <fdparticle/solvers/mumps.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace fdparticle
{
  namespace
  {
    /// Whether the owned rows of K have exactly the global columns of rows (in any order).
    bool has_rows(const Epetra_CrsMatrix &K, const std::vector<std::vector<int>> &rows)
    {
      if (K.NumMyRows() != int(rows.size()))
        return false;
      for (int r = 0; r < K.NumMyRows(); ++r)
        {
          if (K.NumMyEntries(r) != int(rows[r].size()))
            return false;
          std::vector<long long> next(rows[r].begin(), rows[r].end());
          std::sort(next.begin(), next.end());
          if (NewtonSystem::sorted_columns(K.Graph(), r) != next)
            return false;
        }
      return true;
    }

    /// MUMPS's ICNTL(7) for each ordering it can compute itself. Debian's MUMPS has none
    /// of METIS or SCOTCH built in, so "metis" is computed here and handed over as a user
    /// ordering (ICNTL(7) = 1).
    int mumps_ordering_code(const std::string &name)
    {
      if (name == "amd")
        return 0;
      if (name == "metis")
        return 1;
      if (name == "amf")
        return 2;
      if (name == "pord")
        return 4;
      if (name == "qamd")
        return 6;
      return 7; // auto
    }

    std::string mumps_ordering_name(const int code)
    {
      switch (code)
        {
          case 0: return "AMD";
          case 1: return "user (METIS nested dissection)";
          case 2: return "AMF";
          case 3: return "SCOTCH";
          case 4: return "PORD";
          case 5: return "METIS";
          case 6: return "QAMD";
          default: return std::to_string(code);
        }
    }

    /// What the two out-of-memory stops advise.
    const std::string use_iterative_solver =
      "'Solver/Linear solver = iterative' needs about half the memory and grows linearly "
      "with the unknowns (doc/scaling.md).";

  } // namespace

  DirectSolver::DirectSolver()  = default;
  DirectSolver::~DirectSolver()
  {
    // The factorization refers to K: end it first (members go in reverse order of
    // declaration, which would destroy K before the solver that MUMPS still reads it
    // through while it shuts down).
    solver.reset();
    problem.reset();
  }

  void DirectSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Solver");
    {
      prm.declare_entry("Direct solver", "Amesos_Mumps",
                        Patterns::Selection("Amesos_Mumps|Amesos_Klu"),
                        "Direct solver: the factorization of the finite-element block, MUMPS "
                        "(parallel) or KLU (serial, gathers the matrix on one rank).");
      prm.declare_entry("MUMPS ordering", "default",
                        Patterns::Selection("default|metis|auto|amd|amf|qamd|pord"),
                        "Fill-reducing ordering for MUMPS (ICNTL(7)). metis: METIS nested "
                        "dissection computed by fdparticle and given to MUMPS (Debian's MUMPS has "
                        "no METIS of its own); in 3D the fewest flops. qamd: MUMPS's approximate "
                        "minimum degree; in 2D as few flops at a fifth of the analysis. default: "
                        "metis in 3D, qamd in 2D, the fastest measured (doc/performance.md). "
                        "auto: MUMPS's choice (PORD); amd, amf: more flops.");
      prm.declare_entry("Direct solver memory", "0", Patterns::Double(0),
                        "Largest memory, in GB per MPI rank, that the MUMPS factorization may "
                        "need by its analysis's estimate (INFOG(16)); a larger one stops the run "
                        "with a message before anything is allocated. 0: no limit (the run stops "
                        "when an allocation fails). Set it to fail early instead of running the "
                        "machine out of memory.");
      prm.declare_entry("Direct solver statistics", "false", Patterns::Bool(),
                        "Print, for every factorization, its wall time and (MUMPS) the "
                        "ordering used, the flops and the number of entries in the factors.");
    }
    prm.leave_subsection();
  }

  void DirectSolver::parse_parameters(ParameterHandler &prm, const unsigned int dim)
  {
    prm.enter_subsection("Solver");
    solver_type    = prm.get("Direct solver");
    mumps_ordering = prm.get("MUMPS ordering");
    if (mumps_ordering == "default")
      mumps_ordering = dim == 3 ? "metis" : "qamd";
    verbose        = prm.get_bool("Direct solver statistics");
    memory_limit_mb = 1000 * prm.get_double("Direct solver memory");
    prm.leave_subsection();
  }

  void DirectSolver::pattern_changed()
  {
    // The factorization refers to A's Epetra matrix or to K: released before they change.
    solver.reset();
    problem.reset();
    Z.reset();
    K.reset();
    factored      = nullptr;
    symbolic_done = numeric_done = schur_done = false;
  }

  void DirectSolver::operator_changed()
  {
    // New values, same pattern of A: the symbolic factorization of A stays valid; K is
    // rebuilt at the next solve, and its pattern decides about its analysis.
    numeric_done = schur_done = false;
  }

  void DirectSolver::assemble_bordered(const NewtonSystem &system)
  {
    const Epetra_CrsMatrix &E    = system.A.trilinos_matrix();
    const MPI_Comm          comm = system.A.get_mpi_communicator();
    const bool              root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
    const unsigned int      m    = system.D.rows();
    const int               n    = E.NumGlobalRows();
    const int               n_local = E.NumMyRows();

    // The owned rows of A with the columns of B that are non-zero in them.
    std::vector<std::vector<int>>    columns(n_local + (root ? m : 0));
    std::vector<std::vector<double>> values(columns.size());
    for (int r = 0; r < n_local; ++r)
      {
        int     length;
        double *v;
        int *   c;
        E.ExtractMyRowView(r, length, v, c);
        for (int k = 0; k < length; ++k)
          {
            columns[r].push_back(E.GCID(c[k]));
            values[r].push_back(v[k]);
          }
      }
    system.for_each_border_entry(system.B, [&](const int r, const unsigned int j, const double v) {
      columns[r].push_back(n + j);
      values[r].push_back(v);
    });
    // The rows of C: their non-zeros, gathered on rank 0 as (row, column, value).
    std::vector<double> local_c;
    system.for_each_border_entry(system.C_transposed,
                                 [&](const int r, const unsigned int i, const double v) {
                                   local_c.insert(local_c.end(), {double(i), double(E.GRID(r)), v});
                                 });
    const std::vector<std::vector<double>> all_c = dealii::Utilities::MPI::gather(comm, local_c, 0);
    if (root)
      {
        for (const std::vector<double> &part : all_c)
          for (std::size_t e = 0; e < part.size(); e += 3)
            {
              columns[n_local + int(part[e])].push_back(int(part[e + 1]));
              values[n_local + int(part[e])].push_back(part[e + 2]);
            }
        // D, with its diagonal always: for a neutrally buoyant particle it is 0, and the
        // row still needs its pivot position in the pattern.
        const Eigen::SparseMatrix<double, Eigen::RowMajor> D = system.D;
        for (unsigned int i = 0; i < m; ++i)
          {
            columns[n_local + i].push_back(n + i);
            values[n_local + i].push_back(D.coeff(i, i));
            for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator e(D, i); e; ++e)
              if (e.col() != int(i))
                {
                  columns[n_local + i].push_back(n + e.col());
                  values[n_local + i].push_back(e.value());
                }
          }
      }

    const bool new_pattern = dealii::Utilities::MPI::logical_or(!K || !has_rows(*K, columns), comm);

    std::vector<int> gids(columns.size());
    for (int r = 0; r < n_local; ++r)
      gids[r] = E.GRID(r);
    for (unsigned int i = 0; root && i < m; ++i)
      gids[n_local + i] = n + i;
    if (new_pattern)
      {
        // Amesos refers to K: a new K needs a new analysis.
        solver.reset();
        problem.reset();
        symbolic_done = false;
        const Epetra_Map map(n + int(m), int(gids.size()), gids.data(), 0, E.Comm());
        std::vector<int> lengths(columns.size());
        for (std::size_t r = 0; r < columns.size(); ++r)
          lengths[r] = columns[r].size();
        K = std::make_unique<Epetra_CrsMatrix>(Copy, map, lengths.data(), true);
        for (std::size_t r = 0; r < columns.size(); ++r)
          AssertThrow(K->InsertGlobalValues(gids[r], lengths[r], values[r].data(),
                                            columns[r].data()) == 0,
                      ExcInternalError());
        AssertThrow(K->FillComplete() == 0, ExcInternalError());
      }
    else
      for (std::size_t r = 0; r < columns.size(); ++r)
        AssertThrow(K->ReplaceGlobalValues(gids[r], columns[r].size(), values[r].data(),
                                           columns[r].data()) == 0,
                    ExcInternalError());
  }

  void DirectSolver::factorize_symbolic(const MPI_Comm comm)
  {
    const dealii::Timer timer;
    // Amesos takes a non-const operator but only reads it.
    Epetra_CrsMatrix &E = const_cast<Epetra_CrsMatrix &>(*factored);
    problem             = std::make_unique<Epetra_LinearProblem>();
    problem->SetOperator(&E);

    Amesos factory;
    AssertThrow(factory.Query(solver_type),
                ExcMessage("This Trilinos has no " + solver_type + "."));
    solver.reset(factory.Create(solver_type, *problem));
    AssertThrow(solver, ExcMessage("Amesos could not create " + solver_type + "."));

    Teuchos::ParameterList parameters;
    if (solver_type == "Amesos_Mumps")
      {
        Teuchos::ParameterList &controls = parameters.sublist("mumps");
        controls.set("ICNTL(7)", mumps_ordering_code(mumps_ordering));
        controls.set("ICNTL(14)", workspace_percent);
        if (mumps_ordering == "metis")
          {
            permutation = mumps::nested_dissection(E, comm);
            controls.set("PermIn", permutation.empty() ? static_cast<int *>(nullptr) :
                                                      permutation.data());
          }
      }
    AssertThrow(solver->SetParameters(parameters) == 0,
                ExcMessage("Amesos rejected the parameters of " + solver_type + "."));
    AssertThrow(solver->SymbolicFactorization() == 0,
                ExcMessage(solver_type + ": the symbolic factorization failed."));
    // INFOG(16): the analysis' estimate of the factorization's memory on the rank that
    // needs most (MB, in core); the same on every rank.
    if (auto *amesos_mumps = dynamic_cast<Amesos_Mumps *>(solver.get());
        amesos_mumps != nullptr && memory_limit_mb > 0 && amesos_mumps->GetINFOG()[15] > memory_limit_mb)
      throw OutOfMemory(solver_type + ": the factorization would need about " +
                        std::to_string(amesos_mumps->GetINFOG()[15]) + " MB on one rank, more than "
                        "'Solver/Direct solver memory' allows; " + use_iterative_solver);
    symbolic_done = true;
    ++stats.n_symbolic;
    const double t = timer.wall_time();
    stats.symbolic_seconds += t;
    if (verbose && dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      std::cout << "  direct solver " << solver_type << ": symbolic factorization "
                << std::fixed << std::setprecision(3) << t << " s" << std::defaultfloat
                << std::endl;
  }

  void DirectSolver::factorize_numeric(const MPI_Comm comm)
  {
    if (!symbolic_done)
      factorize_symbolic(comm);
    const dealii::Timer timer;
    // MUMPS sizes its work arrays from the analysis' estimate plus ICNTL(14) percent; with
    // many delayed pivots (the saddle point) the estimate can be short (INFOG(1) = -9 at
    // 2D h = 1/256). Then redo the analysis with more margin.
    for (int attempt = 0;; ++attempt)
      {
        if (solver->NumericFactorization() == 0)
          break;
        auto *    amesos_mumps = dynamic_cast<Amesos_Mumps *>(solver.get());
        const int info  = amesos_mumps ? amesos_mumps->GetINFOG()[0] : 0;
        // The factors do not fit in the machine's memory: a shorter time step gives the
        // same matrix pattern and the same factors, so the run stops (OutOfMemory) instead
        // of halving Δt.
        if (info == mumps::out_of_memory)
          {
            std::ostringstream asked;
            asked << std::setprecision(2) << mumps::count(amesos_mumps->GetINFOG()[1]);
            throw OutOfMemory(
              solver_type + " could not allocate " + asked.str() +
              " entries for the factorization (MUMPS INFOG(1) = -13, out of memory): the "
              "direct solver does not fit this problem on this machine; " +
              use_iterative_solver);
          }
        AssertThrow(mumps::short_of_workspace(info) && attempt < mumps::max_workspace_retries,
                    ExcMessage(solver_type + ": the numeric factorization failed" +
                               (amesos_mumps ? " (MUMPS INFOG(1) = " + std::to_string(info) + ")" :
                                        std::string()) +
                               (info == mumps::singular ?
                                  ": the Newton matrix is singular (a particle not resolved "
                                  "by the mesh, too few cells inside it?)." :
                                  ".")));
        workspace_percent *= mumps::workspace_growth;
        if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
          std::cout << "  direct solver: MUMPS ran out of working space (INFOG(1) = " << info
                    << "); analysing again with ICNTL(14) = " << workspace_percent << std::endl;
        factorize_symbolic(comm);
      }
    numeric_done = true;
    schur_done   = false; // Z and S belong to the previous values
    ++stats.n_numeric;
    const double t = timer.wall_time();
    stats.numeric_seconds += t;
    if (verbose)
      report_factorization(t, comm);
  }

  void DirectSolver::report_factorization(const double seconds, const MPI_Comm comm) const
  {
    if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
      return;
    std::cout << "  direct solver " << solver_type << ": numeric factorization " << std::fixed
              << std::setprecision(3) << seconds << " s" << std::defaultfloat;
    if (auto *amesos_mumps = dynamic_cast<Amesos_Mumps *>(solver.get()))
      {
        const int *   infog  = amesos_mumps->GetINFOG();
        const double *rinfog = amesos_mumps->GetRINFOG();
        // INFOG(7): ordering used; RINFOG(3): flops of the elimination; INFOG(29): entries
        // in the factors; INFOG(13): delayed pivots; INFOG(19): MB allocated in total.
        std::cout << ", ordering " << mumps_ordering_name(infog[6]) << ", " << std::setprecision(3)
                  << rinfog[2] << " flops (" << rinfog[2] / seconds / 1e9 << " GFlop/s), "
                  << mumps::count(infog[28]) << " entries in the factors, " << infog[12]
                  << " delayed pivots, " << infog[18] << " MB";
      }
    std::cout << std::endl;
  }

  void DirectSolver::forward_backward(Epetra_MultiVector &rhs, Epetra_MultiVector &sol,
                                      const MPI_Comm comm)
  {
    const dealii::Timer timer;
    problem->SetLHS(&sol);
    problem->SetRHS(&rhs);
    AssertThrow(solver->Solve() == 0, ExcMessage(solver_type + ": the solve failed."));
    problem->SetLHS(nullptr);
    problem->SetRHS(nullptr);
    ++stats.n_solves;
    const double t = timer.wall_time();
    stats.solve_seconds += t;
    if (verbose && dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      std::cout << "  direct solver " << solver_type << ": solve with " << rhs.NumVectors()
                << " right-hand side(s) " << std::fixed << std::setprecision(3) << t << " s"
                << std::defaultfloat << std::endl;
  }

  LinearSolver::SolveInfo DirectSolver::solve(const NewtonSystem &system, const double,
                                               TrilinosWrappers::MPI::Vector &x, Eigen::VectorXd &y)
  {
    const bool bordered = system.D.rows() > max_schur_unknowns;
    const bool setup    = !numeric_done;
    if (setup)
      {
        if (bordered)
          assemble_bordered(system);
        factored = bordered ? K.get() : &system.A.trilinos_matrix();
        factorize_numeric(system.A.get_mpi_communicator());
      }
    SolveInfo info = bordered ? solve_bordered(system, x, y) : solve_by_schur(system, x, y);
    info.setup     = setup;
    return info;
  }

  LinearSolver::SolveInfo DirectSolver::solve_bordered(const NewtonSystem &system,
                                                        TrilinosWrappers::MPI::Vector &x,
                                                        Eigen::VectorXd &y)
  {
    const MPI_Comm     comm  = system.A.get_mpi_communicator();
    const bool         root  = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
    const unsigned int m     = system.D.rows();

    Epetra_Vector rhs(K->RangeMap()), sol(K->DomainMap());
    const int     n_local = system.r_fe.trilinos_vector().MyLength();
    {
      const double *r = system.r_fe.trilinos_vector()[0];
      for (int i = 0; i < n_local; ++i)
        rhs[i] = -r[i];
      for (unsigned int i = 0; root && i < m; ++i)
        rhs[n_local + i] = -system.r_p[i];
    }
    forward_backward(rhs, sol, comm);

    x.reinit(system.r_fe.locally_owned_elements(), comm);
    std::copy_n(&sol[0], n_local, x.trilinos_vector()[0]);
    std::vector<double> particle_part(m, 0.0);
    if (root)
      std::copy_n(sol.Values() + n_local, m, particle_part.data());
    particle_part = dealii::Utilities::MPI::broadcast(comm, particle_part, 0);
    y = Eigen::Map<const Eigen::VectorXd>(particle_part.data(), m);
    return SolveInfo{1, 0.0};
  }

  LinearSolver::SolveInfo DirectSolver::solve_by_schur(const NewtonSystem &system,
                                                        TrilinosWrappers::MPI::Vector &x,
                                                        Eigen::VectorXd &y)
  {
    const unsigned int m = system.n_particle_unknowns();
    // Z = A⁻¹B and the LU of S = D − C Z belong to the Jacobian: computed with its first
    // solve, kept for the later ones (modified Newton), which then need one right-hand side.
    const bool         new_schur = !schur_done && m > 0;
    const unsigned int n_rhs     = new_schur ? m + 1 : 1;

    // One solve for the right-hand sides (−r_fe[, B_1, …, B_m]): column 0 gives
    // z0 = −A⁻¹ r_fe, column j + 1 gives Z_j = A⁻¹ B_j.
    const Epetra_CrsMatrix &E = system.A.trilinos_matrix();
    Epetra_MultiVector      rhs(E.RangeMap(), n_rhs), sol(E.DomainMap(), n_rhs);
    const int               n_local = rhs.MyLength();
    {
      const double *r = system.r_fe.trilinos_vector()[0];
      for (int i = 0; i < n_local; ++i)
        rhs[0][i] = -r[i];
      if (new_schur)
        system.for_each_border_entry(system.B,
                                     [&](const int r, const unsigned int j, const double v) {
                                       rhs[j + 1][r] = v;
                                     });
    }
    const MPI_Comm comm = system.r_fe.get_mpi_communicator();
    forward_backward(rhs, sol, comm);

    x.reinit(system.r_fe.locally_owned_elements(), comm);
    double *xv = x.trilinos_vector()[0];
    std::copy_n(sol[0], n_local, xv);
    y.setZero(m);
    const SolveInfo exact{1, 0.0};
    if (m == 0)
      return exact;

    // G = C·[z0(, Z_1, …, Z_m)]: local products, then one reduction.
    std::vector<double> G(m * n_rhs, 0.0);
    system.for_each_border_entry(system.C_transposed,
                                 [&](const int r, const unsigned int i, const double v) {
                                   for (unsigned int j = 0; j < n_rhs; ++j)
                                     G[i * n_rhs + j] += v * sol[j][r];
                                 });
    dealii::Utilities::MPI::sum(G, comm, G);

    if (new_schur)
      {
        Eigen::MatrixXd S = Eigen::MatrixXd(system.D);
        for (unsigned int i = 0; i < m; ++i)
          for (unsigned int j = 0; j < m; ++j)
            S(i, j) -= G[i * n_rhs + j + 1];
        // Full pivoting: S is tiny, and for neutrally buoyant particles D = 0.
        schur_lu.compute(S);
        AssertThrow(schur_lu.isInvertible(),
                    ExcMessage("The particle block of the Newton system is singular: a "
                               "particle is not resolved by the mesh (too few cells inside "
                               "it?)."));
        Z = std::make_unique<Epetra_MultiVector>(E.DomainMap(), m);
        for (unsigned int j = 0; j < m; ++j)
          std::copy_n(sol[j + 1], n_local, (*Z)[j]);
        schur_done = true;
      }

    Eigen::VectorXd g = -system.r_p;
    for (unsigned int i = 0; i < m; ++i)
      g[i] -= G[i * n_rhs];
    y = schur_lu.solve(g);
    for (unsigned int j = 0; j < m; ++j)
      {
        const double *z = (*Z)[j];
        for (int k = 0; k < n_local; ++k)
          xv[k] -= y[j] * z[k];
      }
    return exact;
  }

} // namespace fdparticle
