#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <fdparticle/solvers/block_preconditioner.h>

#include <EpetraExt_MatrixMatrix.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>

#include <algorithm>
#include <iostream>

namespace fdparticle
{
  namespace
  {
    constexpr unsigned int velocity_block   = NewtonSystem::Blocks::velocity,
                           multiplier_block = NewtonSystem::Blocks::multiplier,
                           pressure_block   = NewtonSystem::Blocks::pressure;

    /// Adds the wall time of its scope to total.
    class ScopedSeconds
    {
    public:
      explicit ScopedSeconds(double &total)
        : total(total)
      {}
      ~ScopedSeconds() { total += timer.wall_time(); }

    private:
      double &    total;
      const Timer timer;
    };

    /// Local entries of a Trilinos vector (nullptr-safe for empty ones).
    double *values(TrilinosWrappers::MPI::Vector &v) { return v.trilinos_vector()[0]; }
    const double *values(const TrilinosWrappers::MPI::Vector &v)
    {
      return v.trilinos_vector()[0];
    }
  } // namespace

  BlockPreconditioner::BlockPreconditioner()  = default;
  BlockPreconditioner::~BlockPreconditioner() = default;

  void BlockPreconditioner::clear()
  {
    patch.clear();
    patch_active = false;
    apply_seconds = patch_apply_seconds = 0;
    times = ApplicationTimes();
    n_patch      = 0;
    velocity_amg.clear();
    velocity_inverse.reset();
    multiplier_amg.clear();
    pressure_amg.clear();
    pressure_laplacian.reset();
    velocity_matrix.reset();
    multiplier_matrix.reset();
    coupling_matrix.reset();
    gradient_matrix.reset();
    column_values.reset();
    coupled_velocity_rows.clear();
  }

  void BlockPreconditioner::gradient_product(const double *p, double *y) const
  {
    const Epetra_CrsMatrix &E = system->A.trilinos_matrix();
    if (!column_values)
      column_values = std::make_unique<Epetra_Vector>(E.ColMap());
    column_values->PutScalar(0);
    double *yc = column_values->Values();
    for (unsigned int r = 0; r < owned[pressure_block].n_elements(); ++r)
      {
        int     n;
        double *v;
        int *   c;
        E.ExtractMyRowView(local_offset[pressure_block] + r, n, v, c);
        for (int k = 0; k < n; ++k)
          yc[c[k]] += v[k] * p[r];
      }
    // Columns of other ranks' DoFs are added at their owners; the pressure columns' sums
    // (the pressure block's own entries) are left out.
    const unsigned int n_u = owned[velocity_block].n_elements();
    if (const Epetra_Import *importer = E.Importer())
      {
        full = 0;
        full.trilinos_vector().Export(*column_values, *importer, Add);
        std::copy_n(values(full) + local_offset[velocity_block], n_u, y);
      }
    else
      std::copy_n(yc + local_offset[velocity_block], n_u, y);
  }

  void BlockPreconditioner::coupling_product(const TrilinosWrappers::MPI::Vector &l,
                                             double *                             y) const
  {
    const Epetra_CrsMatrix &E = system->A.trilinos_matrix();
    full = 0;
    scatter_multipliers(l, values(full) + local_offset[multiplier_block]);
    // Without an importer A's columns are its rows, in their order: full itself.
    const Epetra_Import *importer = E.Importer();
    if (importer)
      {
        if (!column_values)
          column_values = std::make_unique<Epetra_Vector>(E.ColMap());
        column_values->Import(full.trilinos_vector(), *importer, Insert);
      }
    const double *xc = importer ? column_values->Values() : values(full);
    std::fill_n(y, owned[velocity_block].n_elements(), 0.0);
    for (const unsigned int r : coupled_velocity_rows)
      {
        int     n;
        double *v;
        int *   c;
        E.ExtractMyRowView(local_offset[velocity_block] + r, n, v, c);
        // full is zero outside the free multipliers: the rows' pressure entries add 0.
        double sum = 0;
        for (int k = 0; k < n; ++k)
          sum += v[k] * xc[c[k]];
        y[r] = sum;
      }
  }

  std::unique_ptr<Epetra_CrsMatrix>
  BlockPreconditioner::extract(const unsigned int               row_block,
                               const std::vector<unsigned int> &col_blocks) const
  {
    const Epetra_CrsMatrix &E      = system->A.trilinos_matrix();
    const auto &            blocks = system->blocks;
    const MPI_Comm          comm   = system->A.get_mpi_communicator();
    const bool              multiplier_rows = row_block == multiplier_block;
    const bool              multiplier_columns =
      std::find(col_blocks.begin(), col_blocks.end(), multiplier_block) != col_blocks.end();
    const Epetra_Map map = (multiplier_rows ? owned_free_multipliers : owned[row_block])
                             .make_trilinos_map(comm, false);
    auto result = std::make_unique<Epetra_CrsMatrix>(Copy, map, 0);

    // Each column of this rank's part of A: its number in its block (among the free
    // multipliers in the multiplier numbering), or −1 outside col_blocks.
    std::vector<int> column_number(E.NumMyCols(), -1);
    for (int c = 0; c < E.NumMyCols(); ++c)
      {
        const auto [b, j] = blocks.locate(E.GCID(c));
        if (std::find(col_blocks.begin(), col_blocks.end(), b) != col_blocks.end())
          column_number[c] = static_cast<int>(j);
      }
    if (multiplier_columns)
      column_number = free_multiplier_numbers(column_number);
    std::vector<int> rows;
    if (multiplier_rows)
      rows.assign(free_multipliers.begin(), free_multipliers.end());
    else
      for (unsigned int r = 0; r < owned[row_block].n_elements(); ++r)
        rows.push_back(r);
    const int first_row = multiplier_rows ? first_free_multiplier() : 0;
    std::vector<std::pair<int, double>> row;
    std::vector<int>                    cols;
    std::vector<double>                 vals;
    for (unsigned int k = 0; k < rows.size(); ++k)
      {
        const int r     = rows[k];
        const int local = local_offset[row_block] + r;
        int       n;
        double *  v;
        int *     c;
        E.ExtractMyRowView(local, n, v, c);
        row.clear();
        for (int k = 0; k < n; ++k)
          if (column_number[c[k]] >= 0)
            row.emplace_back(column_number[c[k]], v[k]);
        std::sort(row.begin(), row.end(),
                  [](const auto &a, const auto &b) { return a.first < b.first; });
        cols.clear();
        vals.clear();
        for (const auto &[j, value] : row)
          if (!cols.empty() && cols.back() == j)
            vals.back() += value;
          else
            {
              cols.push_back(j);
              vals.push_back(value);
            }
        result->InsertGlobalValues(multiplier_rows ?
                                     first_row + static_cast<int>(k) :
                                     static_cast<int>(blocks.locate(E.GRID(local)).second),
                                   cols.size(), vals.data(), cols.data());
      }
    // Blocks that share a numbering share their owned set too (NewtonSystem::Blocks).
    Assert(std::all_of(col_blocks.begin(), col_blocks.end(),
                       [&](const unsigned int b) { return owned[b] == owned[col_blocks.front()]; }),
           ExcInternalError());
    result->FillComplete((multiplier_columns ? owned_free_multipliers : owned[col_blocks.front()])
                           .make_trilinos_map(comm, false),
                         map);
    return result;
  }

  int BlockPreconditioner::first_free_multiplier() const
  {
    return owned_free_multipliers.is_empty() ?
             0 :
             static_cast<int>(owned_free_multipliers.nth_index_in_set(0));
  }

  void BlockPreconditioner::apply_multiplier_inverse() const
  {
    if (owned_free_multipliers.size() > 0)
      multiplier_amg.vmult(l_out, l_in);
  }

  void BlockPreconditioner::gather_multipliers(const double *                 multipliers,
                                               TrilinosWrappers::MPI::Vector &l) const
  {
    double *v = values(l);
    for (unsigned int k = 0; k < free_multipliers.size(); ++k)
      v[k] = multipliers[free_multipliers[k]];
  }

  void BlockPreconditioner::scatter_multipliers(const TrilinosWrappers::MPI::Vector &l,
                                                double *multipliers) const
  {
    const double *v = values(l);
    for (unsigned int k = 0; k < free_multipliers.size(); ++k)
      multipliers[free_multipliers[k]] = v[k];
  }

  std::vector<int>
  BlockPreconditioner::free_multiplier_numbers(const std::vector<int> &block_numbers) const
  {
    const MPI_Comm   comm = system->A.get_mpi_communicator();
    const Epetra_Map source = owned[multiplier_block].make_trilinos_map(comm, false);
    Epetra_Vector number(source);
    number.PutScalar(-1);
    const double first = first_free_multiplier();
    for (unsigned int k = 0; k < free_multipliers.size(); ++k)
      number[free_multipliers[k]] = first + k;
    std::vector<int> wanted;
    for (const int j : block_numbers)
      if (j >= 0)
        wanted.push_back(j);
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    const Epetra_Map    target(-1, static_cast<int>(wanted.size()), wanted.data(), 0,
                            source.Comm());
    Epetra_Vector       found(target);
    const Epetra_Import import(target, source);
    found.Import(number, import, Insert);
    std::vector<int> result(block_numbers.size(), -1);
    for (unsigned int i = 0; i < block_numbers.size(); ++i)
      if (block_numbers[i] >= 0)
        result[i] = static_cast<int>(
          found[std::lower_bound(wanted.begin(), wanted.end(), block_numbers[i]) - wanted.begin()]);
    return result;
  }

  void BlockPreconditioner::initialize(const NewtonSystem &system_, const BorderedOperator &op_)
  {
    const Timer setup_timer;
    clear();
    system = &system_;
    op     = &op_;
    const auto &   blocks    = system->blocks;
    const IndexSet all_owned = system->r_fe.locally_owned_elements();
    const MPI_Comm comm      = system->r_fe.get_mpi_communicator();
    const unsigned int rank  = Utilities::MPI::this_mpi_process(comm);
    AssertThrow(blocks.range.size() == Utilities::MPI::n_mpi_processes(comm) &&
                  blocks.pressure_dofs_per_cell > 0,
                ExcMessage("The Newton system has no block layout for the iterative solver."));
    owned.resize(NewtonSystem::Blocks::n_blocks);
    local_offset.assign(NewtonSystem::Blocks::n_blocks, 0);
    for (unsigned int b = 0; b < NewtonSystem::Blocks::n_blocks; ++b)
      {
        owned[b] = IndexSet(blocks.size(b));
        owned[b].add_range(blocks.offset[rank][b],
                           blocks.offset[rank][b] + (blocks.range[rank][b + 1] - blocks.range[rank][b]));
        local_offset[b] = blocks.range[rank][b] - blocks.range[rank][0];
      }
    full.reinit(all_owned, comm);
    pressure_part.reinit(all_owned, comm);
    u_in.reinit(owned[velocity_block], comm);
    u_out.reinit(owned[velocity_block], comm);
    free_multipliers.clear();
    {
      const unsigned int o_l = local_offset[multiplier_block];
      const unsigned int n_l = owned[multiplier_block].n_elements();
      for (const unsigned int i : blocks.free_dofs)
        if (i >= o_l && i < o_l + n_l)
          free_multipliers.push_back(i - o_l);
      owned_free_multipliers =
        Utilities::MPI::create_ascending_partitioning(comm, free_multipliers.size())[rank];
    }
    l_in.reinit(owned_free_multipliers, comm);
    l_out.reinit(owned_free_multipliers, comm);
    p_in.reinit(owned[pressure_block], comm);
    p_out.reinit(owned[pressure_block], comm);
    op->reinit_vector(inner_rhs);
    n_inner_iterations = 0;

    initialize_velocity_and_multiplier();
    initialize_pressure_cells();
    if (laplacian_needed())
      initialize_pressure_laplacian();
    initialize_particle_block();
    // A patch that is too large or cannot be factored is dropped (on all ranks, which
    // factor it together): the preconditioner still works without it (the cheap form may
    // then stall and hand over to the inner solve), and a smaller time step would not make
    // it fit.
    const Timer       patch_timer;
    const std::string failure =
      patch_layers >= 0 ?
        patch.initialize(*system, patch_layers, patch_fluid_fraction, patch_memory_limit,
                         symmetrize_patch) :
        "";
    if (!failure.empty())
      {
        if (rank == 0 && !patch_failure_reported)
          std::cerr << "  warning: the cut-cell patch of the iterative solver was not "
                       "factored ("
                    << failure
                    << "); the solver goes on without it, with more iterations "
                       "(Solver/Cut cell patch memory, doc/scaling.md)."
                    << std::endl;
        patch_failure_reported = true;
      }
    n_patch      = Utilities::MPI::sum<types::global_dof_index>(patch.size(), comm);
    patch_active = n_patch > 0;
    patch_seconds = patch_timer.wall_time();
    setup_seconds = setup_timer.wall_time();
  }

  void BlockPreconditioner::initialize_velocity_and_multiplier()
  {
    // K = A_uu, and A_λλ + A_λu in the λ numbering: AMG with the velocity components as
    // near null space (λ has the velocity's numbering, so the same modes).
    TrilinosWrappers::PreconditionAMG::AdditionalData amg;
    amg.elliptic              = true;
    amg.higher_order_elements = true;
    amg.constant_modes        = system->blocks.velocity_modes;
    amg.smoother_sweeps = (system->blocks.velocity_modes.size() == 3 &&
                               system->A.m() >= large_3d_problem ?
                             large_3d_smoother_sweeps :
                             smoother_sweeps);
    amg.aggregation_threshold = velocity_aggregation_threshold;
    amg.coarse_type           = coarse_solver;
    velocity_inverse = system->blocks.velocity_inverse;
    if (velocity_inverse)
      velocity_inverse->initialize(*system, amg);
    else
      {
        velocity_matrix = extract(velocity_block, {velocity_block});
        velocity_amg.initialize(*velocity_matrix, amg);
      }
    amg.aggregation_threshold = multiplier_aggregation_threshold;
    for (std::vector<bool> &mode : amg.constant_modes)
      {
        std::vector<bool> free_mode(free_multipliers.size());
        for (unsigned int k = 0; k < free_multipliers.size(); ++k)
          free_mode[k] = mode[free_multipliers[k]];
        mode.swap(free_mode);
      }
    multiplier_matrix = extract(multiplier_block, {multiplier_block, velocity_block});
    // Without particles no multiplier is free, and S_λ has no rows.
    if (owned_free_multipliers.size() > 0)
      multiplier_amg.initialize(*multiplier_matrix, amg);
    coupled_velocity_rows.clear();
    if (!system->blocks.velocity_product)
      {
        coupling_matrix = extract(velocity_block, {multiplier_block});
        gradient_matrix = extract(velocity_block, {pressure_block});
      }
    else
      {
        const Epetra_CrsMatrix &E = system->A.trilinos_matrix();
        std::vector<bool>       multiplier_column(E.NumMyCols());
        for (int c = 0; c < E.NumMyCols(); ++c)
          multiplier_column[c] = system->blocks.locate(E.GCID(c)).first == multiplier_block;
        for (unsigned int r = 0; r < owned[velocity_block].n_elements(); ++r)
          {
            int     n;
            double *v;
            int *   c;
            E.ExtractMyRowView(local_offset[velocity_block] + r, n, v, c);
            for (int k = 0; k < n; ++k)
              if (multiplier_column[c[k]])
                {
                  coupled_velocity_rows.push_back(r);
                  break;
                }
          }
      }
  }

  void BlockPreconditioner::initialize_pressure_cells()
  {
    // S_p per cell: A's pressure block − (fluid mass + weight · particle mass)/μ.
    const Epetra_CrsMatrix &E   = system->A.trilinos_matrix();
    const auto &            b   = system->blocks;
    const unsigned int      n_p = owned[pressure_block].n_elements();
    const unsigned int      npc = b.pressure_dofs_per_cell;
    pressure_inverse.assign(n_p * npc, 0.0);
    Eigen::MatrixXd S(npc, npc);
    for (unsigned int first = 0; first < n_p; first += npc)
      {
        for (unsigned int i = 0; i < npc; ++i)
          for (unsigned int j = 0; j < npc; ++j)
            {
              const unsigned int k     = (first + i) * npc + j;
              const double       fluid = b.pressure_fluid_mass[k];
              S(i, j) = -(fluid + particle_weight * (b.pressure_mass[k] - fluid)) / b.viscosity;
            }
        const int first_global = E.GRID(local_offset[pressure_block] + first);
        for (unsigned int i = 0; i < npc; ++i)
          {
            int     n;
            double *v;
            int *   c;
            E.ExtractMyRowView(local_offset[pressure_block] + first + i, n, v, c);
            for (int k = 0; k < n; ++k)
              {
                const int j = E.GCID(c[k]) - first_global;
                if (j >= 0 && j < static_cast<int>(npc))
                  S(i, j) += v[k];
              }
          }
        const Eigen::MatrixXd Si = S.fullPivLu().inverse();
        for (unsigned int i = 0; i < npc; ++i)
          for (unsigned int j = 0; j < npc; ++j)
            pressure_inverse[(first + i) * npc + j] = Si(i, j);
      }
  }

  bool BlockPreconditioner::laplacian_needed() const
  {
    if (inertia != Inertia::automatic)
      return inertia == Inertia::always;
    const auto &b = system->blocks;
    return b.slow_pressure_modes > max_slow_pressure_modes ||
           b.inertial_wavenumber() * b.base_cell_size > max_slow_mode_resolution;
  }

  void BlockPreconditioner::initialize_pressure_laplacian()
  {
    // Cahouet–Chabard's second term: L = G M_u⁻¹ Gᵀ, the pressure Laplacian of the
    // lumped (diagonal) velocity mass, with constrained velocities left out.
    const auto    G = extract(pressure_block, {velocity_block});
    Epetra_Vector inverse_mass(G->DomainMap());
    const double *m = values(system->blocks.velocity_mass);
    for (int i = 0; i < inverse_mass.MyLength(); ++i)
      inverse_mass[i] = (m[i] > 0 ? 1.0 / m[i] : 0.0);
    // G M_u⁻¹, in place: G itself is not needed again.
    G->RightScale(inverse_mass);
    // Gᵀ is A's velocity–pressure block (the u–p blocks are transposes, doc/method.md §3),
    // extracted unless it already is: no transpose is formed, and EpetraExt's product with
    // a transposed second factor is many times slower than the plain product.
    const auto gradient = gradient_matrix ? nullptr : extract(velocity_block, {pressure_block});
    Epetra_CrsMatrix product(Copy, G->RowMap(), 0);
    int error = EpetraExt::MatrixMatrix::Multiply(*G, false,
                                                  gradient ? *gradient : *gradient_matrix,
                                                  false, product);
    AssertThrow(error == 0, ExcInternalError());

    // The pressure level is in L's kernel, and a pinned pressure DoF has an empty row:
    // a relative diagonal shift, and 1 on empty rows, keep AMG's coarse factorization
    // regular. The shift goes in first; the product is summed into it.
    Epetra_Vector diagonal(product.RowMap());
    product.ExtractDiagonalCopy(diagonal);
    pressure_laplacian = std::make_unique<Epetra_CrsMatrix>(Copy, product.RowMap(), 0);
    for (int r = 0; r < diagonal.MyLength(); ++r)
      {
        int          row   = product.GRID(r);
        const double shift = (diagonal[r] > 0 ? laplacian_shift * diagonal[r] : 1.0);
        pressure_laplacian->InsertGlobalValues(row, 1, &shift, &row);
      }
    error = EpetraExt::MatrixMatrix::Add(product, false, 1.0, *pressure_laplacian, 1.0);
    AssertThrow(error == 0, ExcInternalError());
    pressure_laplacian->FillComplete(G->RowMap(), G->RowMap());
    TrilinosWrappers::PreconditionAMG::AdditionalData pressure_data;
    pressure_data.elliptic    = true;
    pressure_data.coarse_type = coarse_solver;
    pressure_amg.initialize(*pressure_laplacian, pressure_data);
  }

  void BlockPreconditioner::initialize_particle_block()
  {
    // S_y = D − C S_λ⁻¹ B, block by particle: B's column of unknown j of particle k is
    // non-zero only on k's cells, and S_λ⁻¹ (one V-cycle of A_λλ + M on the free
    // multipliers, those of the particles' cells) reaches little beyond them. So the
    // columns of unknown j of all particles go through one V-cycle together, and each
    // particle reads its own block off the result in its rows: particle_block_size
    // V-cycles, however many particles. What two particles close together do to each other through S_λ⁻¹ lands
    // in their own blocks; D's contact blocks between particles are kept.
    const unsigned int m = op->n_particle_unknowns();
    if (m == 0)
      return;
    const unsigned int size = system->blocks.particle_block_size;
    Assert(size > 0 && m % size == 0, ExcInternalError());
    [[maybe_unused]] const unsigned int n_l = owned[multiplier_block].n_elements();
    const unsigned int                  o_l = local_offset[multiplier_block];

    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(system->D.nonZeros() + m * size);
    for (int j = 0; j < system->D.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator e(system->D, j); e; ++e)
        entries.emplace_back(e.row(), e.col(), e.value());
    for (unsigned int j = 0; j < size; ++j)
      {
        full = 0;
        system->for_each_border_entry(system->B, [&](const int row, const unsigned int column,
                                                     const double value) {
          Assert(row >= int(o_l) && row < int(o_l + n_l), ExcInternalError());
          if (column % size == j)
            values(full)[row] += value;
        });
        gather_multipliers(values(full) + o_l, l_in);
        apply_multiplier_inverse();
        full = 0;
        scatter_multipliers(l_out, values(full) + o_l);
        const Eigen::VectorXd product = system->border_product(full);
        for (unsigned int i = 0; i < m; ++i)
          entries.emplace_back(i, i - i % size + j, -product[i]);
      }
    Eigen::SparseMatrix<double> S(m, m);
    S.setFromTriplets(entries.begin(), entries.end());
    particle_schur.compute(S);
    AssertThrow(particle_schur.info() == Eigen::Success,
                ExcMessage("The particle block of the Newton system is singular: a particle "
                           "is not resolved by the mesh (too few cells inside it?)."));
  }

  void BlockPreconditioner::vmult_rest(BlockVector &dst, const BlockVector &src) const
  {
    const double *     r   = values(src.block(0));
    double *           out = values(dst.block(0));
    const unsigned int n_u = owned[velocity_block].n_elements();
    const unsigned int o_l = local_offset[multiplier_block];

    // λ and y: z = S_λ⁻¹ r_λ, y = S_y⁻¹ (r_y − C z), λ = S_λ⁻¹ (r_λ − B y), on the free
    // multipliers (the others stay 0).
    gather_multipliers(r + o_l, l_in);
    {
      const ScopedSeconds t(times.multiplier_cycles);
      apply_multiplier_inverse();
    }
    const unsigned int m = op->n_particle_unknowns();
    Eigen::VectorXd    y = Eigen::VectorXd::Zero(m);
    if (m > 0)
      {
        {
          const ScopedSeconds t(times.particle_block);
          full = 0;
          scatter_multipliers(l_out, values(full) + o_l);
          y    = particle_schur.solve(op->particle_part(src) - system->border_product(full));
          full = 0;
          system->add_border(y, full);
          const double *by = values(full) + o_l;
          double *      li = values(l_in);
          for (unsigned int k = 0; k < free_multipliers.size(); ++k)
            li[k] -= by[free_multipliers[k]];
        }
        const ScopedSeconds t(times.multiplier_cycles);
        apply_multiplier_inverse();
      }
    op->set_particle_part(dst, y);

    // u = K⁻¹ (r_u − A_uλ λ).
    if (coupling_matrix)
      coupling_matrix->Multiply(false, l_out.trilinos_vector(), u_out.trilinos_vector());
    else
      coupling_product(l_out, values(u_out));
    const double *t  = values(u_out);
    double *      ui = values(u_in);
    for (unsigned int i = 0; i < n_u; ++i)
      ui[i] = r[i] - t[i];
    {
      const ScopedSeconds seconds(times.velocity_cycles);
      if (velocity_inverse)
        velocity_inverse->vmult(u_out, u_in);
      else
        velocity_amg.vmult(u_out, u_in);
    }

    dst.block(0) = 0;
    std::copy_n(values(u_out), n_u, out);
    scatter_multipliers(l_out, out + o_l);
  }

  void BlockPreconditioner::vmult_inner_operator(BlockVector &dst, const BlockVector &src) const
  {
    op->vmult(dst, src);
    std::fill_n(values(dst.block(0)) + local_offset[pressure_block],
                owned[pressure_block].n_elements(), 0.0);
  }

  void BlockPreconditioner::vmult(BlockVector &dst, const BlockVector &src) const
  {
    const Timer timer;
    vmult_blocks(dst, src);
    if (patch_active)
      {
        const double before = timer.wall_time();
        // The particle part of the residual, src − B y (B is non-zero on the particles'
        // cells only); the patch subtracts A dst on its own rows.
        full = 0;
        system->add_border(op->particle_part(dst), full);
        full.sadd(-1.0, 1.0, src.block(0));
        patch.add_correction(dst.block(0), full);
        patch_apply_seconds += timer.wall_time() - before;
      }
    apply_seconds += timer.wall_time();
  }

  void BlockPreconditioner::vmult_blocks(BlockVector &dst, const BlockVector &src) const
  {
    const unsigned int n_p = owned[pressure_block].n_elements();
    const unsigned int o_p = local_offset[pressure_block];
    const unsigned int npc = system->blocks.pressure_dofs_per_cell;

    // p = S_p⁻¹ r_p, cell by cell.
    const double *r = values(src.block(0));
    pressure_part   = 0;
    double *p       = values(pressure_part) + o_p;
    for (unsigned int first = 0; first < n_p; first += npc)
      for (unsigned int i = 0; i < npc; ++i)
        for (unsigned int j = 0; j < npc; ++j)
          p[first + i] += pressure_inverse[(first + i) * npc + j] * r[o_p + first + j];

    // − ρ_f c0 L⁻¹ r_p: Cahouet–Chabard's term, the inertia of the velocity that the
    // pressure has to move (S⁻¹ ≈ −(μ M_p⁻¹ + ρ_f c0 L⁻¹), doc/method.md §8).
    if (pressure_laplacian)
    {
      std::copy_n(r + o_p, n_p, values(p_in));
      pressure_amg.vmult(p_out, p_in);
      const double  alpha = system->blocks.mass_coefficient;
      const double *q     = values(p_out);
      for (unsigned int i = 0; i < n_p; ++i)
        p[i] -= alpha * q[i];
    }

    // J_w w = r_w − J_wp p (only the velocity rows see the pressure: A_up p, a product
    // with a tenth of A's entries).
    if (gradient_matrix)
      {
        std::copy_n(p, n_p, values(p_in));
        gradient_matrix->Multiply(false, p_in.trilinos_vector(), u_out.trilinos_vector());
      }
    else
      gradient_product(p, values(u_out));
    inner_rhs = src;
    {
      double *      ri = values(inner_rhs.block(0));
      const double *t  = values(u_out);
      for (unsigned int i = 0; i < owned[velocity_block].n_elements(); ++i)
        ri[i] -= t[i];
      std::fill_n(ri + o_p, n_p, 0.0);
    }
    struct InnerOperator
    {
      const BlockPreconditioner &self;
      void vmult(BlockVector &d, const BlockVector &s) const { self.vmult_inner_operator(d, s); }
    } inner_operator{*this};
    struct InnerPreconditioner
    {
      const BlockPreconditioner &self;
      void vmult(BlockVector &d, const BlockVector &s) const { self.vmult_rest(d, s); }
    } inner_preconditioner{*this};
    if (!inner_solve)
      {
        // The cheap form: one application of the block triangle of J_w.
        vmult_rest(dst, inner_rhs);
        ++n_inner_iterations;
      }
    else
      {
        SolverControl control(max_inner_iterations, inner_tolerance * inner_rhs.l2_norm(),
                              false, false);
        SolverFGMRES<BlockVector> fgmres(control, SolverFGMRES<BlockVector>::AdditionalData(
                                                    max_inner_iterations));
        dst = 0;
        try
          {
            fgmres.solve(inner_operator, dst, inner_rhs, inner_preconditioner);
          }
        catch (const SolverControl::NoConvergence &)
          {
            // An inexact inner solve is still a preconditioner; the outer FGMRES, which
            // allows one that changes, decides whether the whole solve converges.
          }
        n_inner_iterations += control.last_step();
      }
    std::copy_n(values(pressure_part) + o_p, n_p, values(dst.block(0)) + o_p);
  }
} // namespace fdparticle
