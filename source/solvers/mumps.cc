#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <fdparticle/solvers/mumps.h>

#include <Epetra_CrsMatrix.h>
#include <metis.h>

#include <algorithm>

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

    std::vector<int> nested_dissection(const Epetra_CrsMatrix &E, const MPI_Comm comm)
    {
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

      const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
      const unsigned int rank    = dealii::Utilities::MPI::this_mpi_process(comm);
      const int          my_size = local_edges.size();
      std::vector<int>   sizes(n_ranks), offsets(n_ranks + 1, 0);
      MPI_Gather(&my_size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, comm);
      for (unsigned int p = 0; p < n_ranks; ++p)
        offsets[p + 1] = offsets[p] + sizes[p];
      std::vector<int> edges(rank == 0 ? offsets[n_ranks] : 0);
      MPI_Gatherv(local_edges.data(), my_size, MPI_INT, edges.data(), sizes.data(),
                  offsets.data(), MPI_INT, 0, comm);
      local_edges = std::vector<int>();
      if (rank != 0)
        return {};

      // Adjacency of the symmetrized graph in CSR form: count, fill both directions,
      // then sort and remove duplicates row by row.
      const idx_t      n = E.NumGlobalRows();
      std::vector<idx_t> degree(n + 1, 0);
      for (std::size_t e = 0; e < edges.size(); e += 2)
        {
          ++degree[edges[e] + 1];
          ++degree[edges[e + 1] + 1];
        }
      for (idx_t i = 0; i < n; ++i)
        degree[i + 1] += degree[i];
      std::vector<idx_t> adjacency(degree[n]);
      std::vector<idx_t> fill(degree.begin(), degree.end() - 1);
      for (std::size_t e = 0; e < edges.size(); e += 2)
        {
          adjacency[fill[edges[e]]++]     = edges[e + 1];
          adjacency[fill[edges[e + 1]]++] = edges[e];
        }
      edges = std::vector<int>();
      std::vector<idx_t> xadj(n + 1, 0);
      idx_t              out = 0;
      for (idx_t i = 0; i < n; ++i)
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
      std::vector<idx_t> perm(n), iperm(n);
      idx_t              nv  = n;
      const int          ret = METIS_NodeND(&nv, xadj.data(), adjacency.data(), nullptr, options,
                                   perm.data(), iperm.data());
      AssertThrow(ret == METIS_OK, ExcMessage("METIS_NodeND failed."));
      // iperm[i] is the new (0-based) position of unknown i.
      std::vector<int> perm_in(n);
      for (idx_t i = 0; i < n; ++i)
        perm_in[i] = iperm[i] + 1;
      return perm_in;
    }
  } // namespace mumps
} // namespace fdparticle
