#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/mumps.h>

#include <Epetra_CrsMatrix.h>
#include <dmumps_c.h>
#include <metis.h>

#include <algorithm>
#include <numeric>

namespace fdparticle
{
  namespace mumps
  {
    using namespace dealii;

    bool short_of_workspace(const int infog_1)
    {
      return infog_1 == -8 || infog_1 == -9 || infog_1 == -14 || infog_1 == -15 ||
             infog_1 == -17;
    }

    std::vector<int> nested_dissection(const Epetra_CrsMatrix &E, const MPI_Comm comm,
                                       const std::vector<int> &group)
    {
      Assert(group.empty() || group.size() == static_cast<std::size_t>(E.NumMyRows()),
             ExcDimensionMismatch(group.size(), E.NumMyRows()));
      // Local rows as (global row, global column) pairs, without the diagonal.
      std::vector<int> local_edges;
      local_edges.reserve(2 * E.NumMyNonzeros());
      for (int r = 0; r < E.NumMyRows(); ++r)
        {
          int     n;
          int *   cols;
          double *vals;
          E.ExtractMyRowView(r, n, vals, cols);
          const int row = E.GRID(r);
          for (int k = 0; k < n; ++k)
            {
              const int col = E.GCID(cols[k]);
              if (col != row)
                {
                  local_edges.push_back(row);
                  local_edges.push_back(col);
                }
            }
        }

      // On rank 0: the edges, and the group of every row (each its own without groups).
      const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
      const unsigned int rank    = dealii::Utilities::MPI::this_mpi_process(comm);
      const idx_t        n       = E.NumGlobalRows();
      auto gather = [&](const std::vector<int> &local) {
        const int        my_size = local.size();
        std::vector<int> sizes(n_ranks), offsets(n_ranks + 1, 0);
        MPI_Gather(&my_size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, comm);
        for (unsigned int p = 0; p < n_ranks; ++p)
          offsets[p + 1] = offsets[p] + sizes[p];
        std::vector<int> all(rank == 0 ? offsets[n_ranks] : 0);
        MPI_Gatherv(local.data(), my_size, MPI_INT, all.data(), sizes.data(), offsets.data(),
                    MPI_INT, 0, comm);
        return all;
      };
      std::vector<int> edges = gather(local_edges);
      local_edges            = std::vector<int>();
      std::vector<int> group_of;
      if (dealii::Utilities::MPI::max(static_cast<int>(group.size()), comm) > 0)
        group_of = gather(group);
      if (rank != 0)
        return {};
      AssertThrow(group_of.empty() || group_of.size() == static_cast<std::size_t>(n),
                  ExcMessage("Every rank names the groups of all its rows, or none does."));
      if (group_of.empty())
        {
          group_of.resize(n);
          std::iota(group_of.begin(), group_of.end(), 0);
        }

      // The groups, numbered 0 … n_vertices − 1 in the order of their first rows.
      std::vector<idx_t> group_vertex(n, -1), vertex(n);
      idx_t              n_vertices = 0;
      for (idx_t i = 0; i < n; ++i)
        {
          AssertIndexRange(group_of[i], n);
          if (group_vertex[group_of[i]] < 0)
            group_vertex[group_of[i]] = n_vertices++;
          vertex[i] = group_vertex[group_of[i]];
        }
      group_of     = std::vector<int>();
      group_vertex = std::vector<idx_t>();

      // Adjacency of the symmetrized graph of the groups in CSR form: count, fill both
      // directions, then sort and remove duplicates row by row.
      std::vector<idx_t> degree(n_vertices + 1, 0);
      for (std::size_t e = 0; e < edges.size(); e += 2)
        if (vertex[edges[e]] != vertex[edges[e + 1]])
          {
            ++degree[vertex[edges[e]] + 1];
            ++degree[vertex[edges[e + 1]] + 1];
          }
      for (idx_t i = 0; i < n_vertices; ++i)
        degree[i + 1] += degree[i];
      std::vector<idx_t> adjacency(degree[n_vertices]);
      std::vector<idx_t> fill(degree.begin(), degree.end() - 1);
      for (std::size_t e = 0; e < edges.size(); e += 2)
        {
          const idx_t a = vertex[edges[e]], b = vertex[edges[e + 1]];
          if (a != b)
            {
              adjacency[fill[a]++] = b;
              adjacency[fill[b]++] = a;
            }
        }
      edges = std::vector<int>();
      std::vector<idx_t> xadj(n_vertices + 1, 0);
      idx_t              out = 0;
      for (idx_t i = 0; i < n_vertices; ++i)
        {
          auto first = adjacency.begin() + degree[i], last = adjacency.begin() + degree[i + 1];
          std::sort(first, last);
          last = std::unique(first, last);
          for (auto it = first; it != last; ++it)
            adjacency[out++] = *it;
          xadj[i + 1] = out;
        }
      adjacency.resize(out);

      idx_t options[METIS_NOPTIONS];
      METIS_SetDefaultOptions(options);
      options[METIS_OPTION_NUMBERING] = 0;
      std::vector<idx_t> perm(n_vertices), iperm(n_vertices);
      idx_t              nv  = n_vertices;
      const int          ret = METIS_NodeND(&nv, xadj.data(), adjacency.data(), nullptr, options,
                                   perm.data(), iperm.data());
      AssertThrow(ret == METIS_OK, ExcMessage("METIS_NodeND failed."));
      // iperm[v] is the new (0-based) position of group v; its rows follow each other in
      // ascending order, from the first position of the group (the rows of the groups
      // before it counted).
      std::vector<int> first(n_vertices + 1, 0);
      for (idx_t i = 0; i < n; ++i)
        ++first[iperm[vertex[i]] + 1];
      for (idx_t k = 0; k < n_vertices; ++k)
        first[k + 1] += first[k];
      std::vector<int> perm_in(n);
      for (idx_t i = 0; i < n; ++i)
        perm_in[i] = ++first[iperm[vertex[i]]];
      return perm_in;
    }

    struct Factorization::Instance
    {
      DMUMPS_STRUC_C      id = {};
      bool                root;
      std::vector<int>    rows, columns;
      std::vector<double> values;
    };

    Factorization::Factorization(const MPI_Comm comm, const int n, const bool symmetric,
                                 std::vector<int> rows, std::vector<int> columns,
                                 std::vector<double> values)
      : instance(std::make_unique<Instance>())
    {
      AssertDimension(rows.size(), values.size());
      AssertDimension(columns.size(), values.size());
      for (std::size_t k = 0; k < rows.size(); ++k)
        Assert(!symmetric || rows[k] >= columns[k],
               ExcMessage("A symmetric matrix is given by its lower triangle."));
      // MUMPS numbers from 1.
      for (int &i : rows)
        ++i;
      for (int &j : columns)
        ++j;
      instance->rows    = std::move(rows);
      instance->columns = std::move(columns);
      instance->values  = std::move(values);
      DMUMPS_STRUC_C &id = instance->id;
      instance->root     = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      id.comm_fortran    = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
      id.par             = 1; // rank 0 works too
      id.sym             = symmetric ? 2 : 0; // LDLᵀ (general symmetric) or LU
      id.job             = -1;
      dmumps_c(&id);
      // No output: the caller reports INFOG(1).
      id.icntl[0]  = -1;
      id.icntl[1]  = -1;
      id.icntl[2]  = -1;
      id.icntl[3]  = 0;
      id.icntl[17] = 3; // ICNTL(18): the entries distributed over the ranks
      id.n         = n;
      id.nnz_loc   = instance->values.size();
      id.irn_loc   = instance->rows.data();
      id.jcn_loc   = instance->columns.data();
      id.a_loc     = instance->values.data();
    }

    Factorization::~Factorization()
    {
      instance->id.job = -2;
      dmumps_c(&instance->id);
    }

    int Factorization::analyse(std::vector<int> &ordering, const int workspace_percent)
    {
      DMUMPS_STRUC_C &id = instance->id;
      id.icntl[6]        = ordering.empty() ? 7 : 1; // ICNTL(7): given, or MUMPS's choice
      id.perm_in         = ordering.empty() ? nullptr : ordering.data();
      id.icntl[13]       = workspace_percent; // ICNTL(14)
      id.job             = 1;
      dmumps_c(&id);
      return id.infog[0];
    }

    double Factorization::estimated_memory() const { return 1e6 * instance->id.infog[15]; }

    int Factorization::factor()
    {
      DMUMPS_STRUC_C &id = instance->id;
      id.job             = 2;
      dmumps_c(&id);
      if (id.infog[0] < 0)
        return id.infog[0];
      // Once factored, MUMPS holds its own copy: a solve does not read the entries.
      instance->rows    = std::vector<int>();
      instance->columns = std::vector<int>();
      instance->values  = std::vector<double>();
      id.irn_loc = id.jcn_loc = nullptr;
      id.a_loc                = nullptr;
      return id.infog[0];
    }

    double Factorization::memory() const { return 1e6 * instance->id.infog[17]; }

    int Factorization::solve(std::vector<double> &b)
    {
      DMUMPS_STRUC_C &id = instance->id;
      if (instance->root)
        {
          AssertDimension(b.size(), static_cast<std::size_t>(id.n));
          id.rhs = b.data();
        }
      id.nrhs = 1;
      id.lrhs = id.n;
      id.job  = 3;
      dmumps_c(&id);
      return id.infog[0];
    }
  } // namespace mumps
} // namespace fdparticle
