// Unit test of fdparticle::VelocityOperator (include/fdparticle/fem/velocity_operator.h):
// the matrix-free velocity block equals the velocity block of the Jacobian that
// NavierStokesAssembler assembles, A_uu x, on the unconstrained rows, to 1e-12 of |A_uu x|,
// and so do its diagonal where no constraint ties a DoF to others and its assembled matrix
// (compute_matrix) on the same rows. With the Jacobian assembled without its velocity
// block (the iterative solver's multigrid path), that A plus VelocityBlock's product, and
// plus VelocityBlock's matrix of all cells (the cut-cell patch's rows), equal the whole A.
// Scenes: 2D and 3D boxes with a periodic direction and walls, a mesh refined around a
// sphere (hanging nodes), the sphere cutting cells; Stokes and Navier–Stokes (Newton's
// convection at a random iterate), the Gauss and the level-set cut-cell rules (a Debug
// build: one 3D scene, Navier–Stokes with the level-set rule).
// test-ranks: 1 2

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_tools.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <fdparticle/base/fluid.h>
#include <fdparticle/base/time_stepper.h>
#include <fdparticle/core/simulation.h>
#include <fdparticle/fem/block_numbering.h>
#include <fdparticle/fem/domain.h>
#include <fdparticle/fem/introspection.h>
#include <fdparticle/fem/navier_stokes_assembler.h>
#include <fdparticle/fem/velocity_block.h>
#include <fdparticle/fem/velocity_operator.h>

#include "unit_check.h"

#include <random>
#include <string>

using namespace dealii;
using namespace fdparticle;
using namespace unit_check;

namespace
{
  template <int dim>
  std::string scene(const bool convection, const std::string &cut_cells)
  {
    const std::string centre = (dim == 2 ? "0.43, 0.52" : "0.43, 0.52, 0.47");
    return unit_box_parameters<dim>(4) +
           "subsection Geometry\n  set Periodic directions = x\nend\n"
           "subsection Boundary conditions\n  set Wall velocities = y+: " +
           std::string(dim == 2 ? "1, 0" : "1, 0, 0") +
           "\nend\n"
           "subsection Fluid\n  set Density = 1.3\n  set Viscosity = 0.07\n"
           "  set Convection = " +
           (convection ? "true" : "false") +
           "\nend\n"
           "subsection Particles\n  set Particles = " +
           centre +
           " : 0.2 : 2 : fixed\nend\n"
           "subsection Quadrature\n  set Cut cells = " +
           cut_cells +
           "\nend\n"
           "subsection Time\n  set Time step = 0.01\nend\n";
  }

  template <int dim>
  void check_scene(const bool convection, const std::string &cut_cells)
  {
    const MPI_Comm   comm = MPI_COMM_WORLD;
    ParameterHandler prm;
    declare_all_parameters(prm);
    prm.parse_input_from_string(scene<dim>(convection, cut_cells));
    Domain<dim> domain;
    domain.parse_parameters(prm);
    Fluid<dim> fluid;
    fluid.parse_parameters(prm);
    for (unsigned int d = 0; d < dim; ++d)
      fluid.periodic[d] = domain.is_periodic(d);
    ParticleSet<dim> particles;
    particles.parse_parameters(prm, domain, comm);
    TimeStepper time;
    time.parse_parameters(prm);
    particles.prepare_step(time);
    CutCellQuadrature<dim> quadrature;
    quadrature.parse_parameters(prm);

    // The base mesh, refined twice around the sphere (in 3D in a Debug build, whose
    // assertions are what it checks there, once): cut cells, hanging nodes.
    parallel::distributed::Triangulation<dim> tria(comm);
    domain.create_mesh(tria);
#ifdef DEBUG
    const unsigned int passes = dim == 3 ? 1 : 2;
#else
    const unsigned int passes = 2;
#endif
    for (unsigned int pass = 0; pass < passes; ++pass)
      {
        for (const auto &cell : tria.active_cell_iterators())
          if (cell->is_locally_owned() &&
              cell->center().distance(particles[0].position) < 0.2 + cell->diameter())
            cell->set_refine_flag();
        tria.execute_coarsening_and_refinement();
      }

    // The system: u | λ | p, its constraints and the Jacobian.
    const FESystem<dim> fe = Introspection<dim>::finite_element();
    DoFHandler<dim>     dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    NewtonSystem system;
    number_dofs_by_block(dof_handler, true, system.blocks);
    const IndexSet owned = dof_handler.locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    AffineConstraints<double> constraints(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    domain.make_periodicity_constraints(dof_handler, constraints);
    domain.make_wall_constraints(dof_handler, fe.component_mask(Introspection<dim>::velocities()),
                                 true, constraints);
    constraints.close();
    TrilinosWrappers::SparsityPattern sparsity(owned, owned, relevant, comm);
    DoFTools::make_sparsity_pattern(dof_handler, sparsity, constraints, false,
                                    Utilities::MPI::this_mpi_process(comm));
    sparsity.compress();
    system.reinit(owned, relevant, sparsity, true,
                  NewtonSystem::border_pattern(owned, relevant, 0, comm), comm);

    // A random iterate (u only) and a random x, both in the constrained space.
    std::mt19937                           random(17 + dim);
    std::uniform_real_distribution<double> uniform(-1, 1);
    const auto random_velocity = [&]() {
      TrilinosWrappers::MPI::Vector v(owned, comm);
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < dofs.size(); ++i)
              if (Introspection<dim>::field(fe.system_to_component_index(i).first) ==
                    Introspection<dim>::Field::velocity &&
                  owned.is_element(dofs[i]))
                v[dofs[i]] = uniform(random);
          }
      v.compress(VectorOperation::insert);
      constraints.distribute(v);
      TrilinosWrappers::MPI::Vector ghosted(owned, relevant, comm);
      ghosted = v;
      return std::make_pair(v, ghosted);
    };
    const auto [iterate, iterate_ghosted] = random_velocity();
    const auto [x, x_ghosted]             = random_velocity();
    TrilinosWrappers::MPI::Vector history(owned, relevant, comm);
    const std::array<double, 3>   c = time.coefficients();
    NavierStokesAssembler<dim>    assembler(fe, fluid, particles, quadrature);
    assembler.parse_parameters(prm);
    assembler.assemble(dof_handler, iterate_ghosted, history, c, constraints, true, system);
    TrilinosWrappers::MPI::Vector y(owned, comm);
    system.A.vmult(y, x);

    // The same Jacobian with the velocity block left to VelocityBlock (the iterative
    // solver's multigrid): A' x + K x, and A' x + K_cells x with the velocity block
    // assembled on all cells (the cut-cell patch's rows), equal A x.
    NewtonSystem split;
    split.blocks = system.blocks;
    split.reinit(owned, relevant, sparsity, true,
                 NewtonSystem::border_pattern(owned, relevant, 0, comm), comm);
    std::vector<FullMatrix<double>> cut_matrices;
    assembler.assemble(dof_handler, iterate_ghosted, history, c, constraints, true, split,
                       &cut_matrices);
    VelocityBlock<dim> block(assembler.get_mapping(), domain);
    block.reinit(dof_handler, split.blocks, constraints);
    block.set_jacobian(fluid.density, fluid.viscosity, c[0], fluid.convection ? &iterate : nullptr,
                       cut_matrices);
    TrilinosWrappers::MPI::Vector y_split(owned, comm), y_cells(owned, comm);
    split.A.vmult(y_split, x);
    y_cells = y_split;
    block.vmult_add(y_split, x);
    const auto &range = split.blocks.range[Utilities::MPI::this_mpi_process(comm)];
    const std::vector<bool> all_cells((range[NewtonSystem::Blocks::pressure + 1] -
                                       range[NewtonSystem::Blocks::pressure]) /
                                        split.blocks.pressure_dofs_per_cell,
                                      true);
    TrilinosWrappers::SparseMatrix cells_matrix;
    block.assemble_on_cells(all_cells, cells_matrix);
    cells_matrix.vmult_add(y_cells, x);
    double split_largest = 0, split_difference = 0, cells_difference = 0;
    for (const auto s : owned)
      if (!constraints.is_constrained(s))
        {
          split_largest    = std::max(split_largest, std::abs(y[s]));
          split_difference = std::max(split_difference, std::abs(y[s] - y_split[s]));
          cells_difference = std::max(cells_difference, std::abs(y[s] - y_cells[s]));
        }
    split_largest    = Utilities::MPI::max(split_largest, comm);
    split_difference = Utilities::MPI::max(split_difference, comm);
    cells_difference = Utilities::MPI::max(cells_difference, comm);

    // The velocity-only DoFs of an element on the same mesh with the system's
    // constraints (hanging nodes, periodicity, walls); their relevant DoFs.
    const auto distribute = [&](DoFHandler<dim> &dofs, const FiniteElement<dim> &fe,
                                AffineConstraints<double> &c) {
      dofs.distribute_dofs(fe);
      make_velocity_constraints(domain, dofs, c);
      return c.get_local_lines();
    };
    // The Q2 velocity DoFs, and the operator.
    const FESystem<dim>       velocity_fe(FE_Q<dim>(Introspection<dim>::velocity_degree), dim);
    DoFHandler<dim>           velocity_dofs(tria);
    AffineConstraints<double> velocity_constraints;
    distribute(velocity_dofs, velocity_fe, velocity_constraints);
    VelocityOperator<dim> op;
    op.reinit(assembler.get_mapping(), velocity_dofs, velocity_constraints);

    // Each owned velocity DoF's number in the system, from the cells both numberings share.
    using Vector = typename VelocityOperator<dim>::VectorType;
    Vector x_u, w_u, y_u;
    op.initialize_dof_vector(x_u);
    op.initialize_dof_vector(w_u);
    op.initialize_dof_vector(y_u);
    std::vector<std::pair<types::global_dof_index, types::global_dof_index>> pairs;
    std::vector<types::global_dof_index> system_dofs(fe.n_dofs_per_cell()),
      own_dofs(velocity_fe.n_dofs_per_cell());
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          typename DoFHandler<dim>::active_cell_iterator(&tria, cell->level(), cell->index(),
                                                         &dof_handler)
            ->get_dof_indices(system_dofs);
          typename DoFHandler<dim>::active_cell_iterator(&tria, cell->level(), cell->index(),
                                                         &velocity_dofs)
            ->get_dof_indices(own_dofs);
          for (unsigned int comp = 0; comp < dim; ++comp)
            for (unsigned int a = 0; a < velocity_fe.base_element(0).n_dofs_per_cell(); ++a)
              {
                const auto v = own_dofs[velocity_fe.component_to_system_index(comp, a)];
                const auto s = system_dofs[fe.component_to_system_index(comp, a)];
                if (x_u.locally_owned_elements().is_element(v))
                  pairs.emplace_back(v, s);
              }
        }
    bool same_owner = true;
    for (const auto &[v, s] : pairs)
      {
        same_owner = same_owner && owned.is_element(s);
        x_u[v] = x[s];
        w_u[v] = iterate[s];
      }
    check(Utilities::MPI::min(int(same_owner), comm) == 1,
          "a velocity DoF has the same owner in both numberings");

    op.set_coefficients(fluid.density, fluid.viscosity, c[0], fluid.convection ? &w_u : nullptr);
    op.set_cut_cell_matrices(cut_matrices);
    op.vmult(y_u, x_u);

    double largest = 0, difference = 0;
    for (const auto &[v, s] : pairs)
      if (!velocity_constraints.is_constrained(v) && !constraints.is_constrained(s))
        {
          largest    = std::max(largest, std::abs(y[s]));
          difference = std::max(difference, std::abs(y[s] - y_u[v]));
        }
    largest    = Utilities::MPI::max(largest, comm);
    difference = Utilities::MPI::max(difference, comm);
    // The diagonal, exact where no constraint ties a DoF to others (the masters of hanging
    // nodes and periodic pairs get an approximation, VelocityOperator::compute_diagonal).
    Vector diagonal;
    op.compute_diagonal(diagonal);
    std::vector<bool> tied(velocity_dofs.n_dofs(), false);
    for (const auto &line : velocity_constraints.get_lines())
      {
        tied[line.index] = true;
        for (const auto &entry : line.entries)
          tied[entry.first] = true;
      }
    double largest_diagonal = 0, diagonal_difference = 0;
    unsigned int n_compared = 0;
    for (const auto &[v, s] : pairs)
      if (!tied[v] && !constraints.is_constrained(s))
        {
          largest_diagonal    = std::max(largest_diagonal, std::abs(system.A.diag_element(s)));
          diagonal_difference = std::max(diagonal_difference,
                                         std::abs(system.A.diag_element(s) - diagonal[v]));
          ++n_compared;
        }
    largest_diagonal    = Utilities::MPI::max(largest_diagonal, comm);
    diagonal_difference = Utilities::MPI::max(diagonal_difference, comm);
    n_compared          = Utilities::MPI::sum(n_compared, comm);

    // The operator as a matrix (compute_matrix, a coarse level's AMG): its product equals
    // the operator's on the rows no constraint touches.
    TrilinosWrappers::SparseMatrix matrix;
    op.compute_matrix(velocity_dofs, velocity_constraints, matrix);
    Vector y_m;
    op.initialize_dof_vector(y_m);
    matrix.vmult(y_m, x_u);
    double matrix_difference = 0;
    for (const auto &[v, s] : pairs)
      if (!tied[v])
        matrix_difference = std::max(matrix_difference, std::abs(y_m[v] - y_u[v]));
    matrix_difference = Utilities::MPI::max(matrix_difference, comm);

    // The operator projected on Q1 on the same mesh (compute_matrix with a coarser
    // element: the velocity multigrid's coarsest level): y₁ᵀ A₁ x₁ = (E y₁)ᵀ A (E x₁) for
    // Q1 fields x₁, y₁ in the constrained space and E their interpolation into Q2, both
    // sums over the rows no constraint holds.
    const FESystem<dim>       linear_fe(FE_Q<dim>(1), dim);
    DoFHandler<dim>           linear_dofs(tria);
    AffineConstraints<double> linear_constraints;
    const IndexSet linear_relevant = distribute(linear_dofs, linear_fe, linear_constraints);
    TrilinosWrappers::SparseMatrix linear_matrix;
    op.compute_matrix(linear_dofs, linear_constraints, linear_matrix);
    const auto linear_partitioner = std::make_shared<Utilities::MPI::Partitioner>(
      linear_dofs.locally_owned_dofs(), linear_relevant, comm);
    Vector x_1(linear_partitioner), y_1(linear_partitioner), z_1(linear_partitioner);
    for (unsigned int i = 0; i < x_1.locally_owned_size(); ++i)
      {
        x_1.local_element(i) = uniform(random);
        y_1.local_element(i) = uniform(random);
      }
    Vector x_2, y_2, z_2;
    op.initialize_dof_vector(x_2);
    op.initialize_dof_vector(y_2);
    op.initialize_dof_vector(z_2);
    for (auto [v_1, v_2] : {std::pair(&x_1, &x_2), std::pair(&y_1, &y_2)})
      {
        linear_constraints.distribute(*v_1);
        v_1->update_ghost_values();
        FETools::interpolate(linear_dofs, *v_1, velocity_dofs, velocity_constraints, *v_2);
        v_1->zero_out_ghost_values();
      }
    linear_matrix.vmult(z_1, x_1);
    op.vmult(z_2, x_2);
    const auto free_product = [&](const Vector &a, const Vector &b,
                                  const AffineConstraints<double> &c) {
      double sums[2] = {0, 0};
      const IndexSet &owned_rows = a.get_partitioner()->locally_owned_range();
      for (unsigned int i = 0; i < a.locally_owned_size(); ++i)
        if (!c.is_constrained(owned_rows.nth_index_in_set(i)))
          {
            sums[0] += a.local_element(i) * b.local_element(i);
            sums[1] += std::abs(a.local_element(i) * b.local_element(i));
          }
      Utilities::MPI::sum(ArrayView<const double>(sums, 2), comm, ArrayView<double>(sums, 2));
      return std::pair(sums[0], sums[1]);
    };
    const auto [linear_product, linear_scale] = free_product(y_1, z_1, linear_constraints);
    const auto [quadratic_product, quadratic_scale] = free_product(y_2, z_2, velocity_constraints);

    const double cut_fraction = op.cut_cell_fraction();
    const std::string what = std::to_string(dim) + "D " + (convection ? "Navier-Stokes" : "Stokes") +
                             ", " + cut_cells + " cut cells";
    check(cut_fraction > 0 && cut_fraction < 0.5,
          what + ": some cells are cut, most are not (cut fraction " + std::to_string(cut_fraction) +
            ")");
    check(largest > 0 && difference <= 1e-12 * largest,
          what + ": matrix-free A_uu x equals the assembled one",
          "max difference " + std::to_string(difference) + " of max |A_uu x| " +
            std::to_string(largest));
    check(split_largest > 0 && split_difference <= 1e-12 * split_largest,
          what + ": A without its velocity block plus VelocityBlock multiplies as A",
          "max difference " + std::to_string(split_difference) + " of max |A x| " +
            std::to_string(split_largest));
    check(cells_difference <= 1e-12 * split_largest,
          what + ": A without its velocity block plus the block assembled on all cells multiplies as A",
          "max difference " + std::to_string(cells_difference) + " of max |A x| " +
            std::to_string(split_largest));
    check(matrix_difference <= 1e-12 * largest,
          what + ": the operator's matrix multiplies as the operator does",
          "max difference " + std::to_string(matrix_difference) + " of max |A_uu x| " +
            std::to_string(largest));
    check(linear_scale > 0 &&
            std::abs(linear_product - quadratic_product) <= 1e-12 * quadratic_scale,
          what + ": the Q1 projection of the operator is its Galerkin restriction",
          "y1' A1 x1 = " + std::to_string(linear_product) + ", (E y1)' A (E x1) = " +
            std::to_string(quadratic_product));
    check(n_compared > 0 && diagonal_difference <= 1e-12 * largest_diagonal,
          what + ": the diagonal equals the assembled one where no constraint ties the DoF",
          "max difference " + std::to_string(diagonal_difference) + " of " +
            std::to_string(largest_diagonal) + " over " + std::to_string(n_compared) + " DoFs");
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (const bool convection : {false, true})
    for (const std::string cut_cells : {"gauss", "level set"})
      {
        check_scene<2>(convection, cut_cells);
#ifdef DEBUG
        // In a Debug build deal.II's assertions run on one 3D scene, the one with the
        // most terms: Navier-Stokes with the level-set rule (the four take minutes).
        if (!convection || cut_cells != "level set")
          continue;
#endif
        check_scene<3>(convection, cut_cells);
      }
  return summary();
}
