#ifndef fdparticle_fem_pressure_agglomeration_h
#define fdparticle_fem_pressure_agglomeration_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>

#include <fdparticle/fem/cut_cell_quadrature.h>
#include <fdparticle/particles/particle_set.h>

#include <utility>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * Pressure agglomeration of nearly covered cut cells (doc/method.md §7): the linear
   * pressure of a cut cell whose fluid part is at most `Pressure agglomeration` of its
   * volume is the mean of its face neighbours' linear pressures continued into it, over
   * the neighbours whose fluid part is above that fraction, weighted by their fluid
   * volumes. Constraints tie the cell's pressure DoFs to theirs; a cell without such a
   * neighbour keeps its own pressure. Such a cell's pressure is seen only by its fluid
   * sliver, so it is nearly free; tied to fluid neighbours it is not.
   */
  template <int dim>
  class PressureAgglomeration
  {
  public:
    static void declare_parameters(ParameterHandler &prm);
    void        parse_parameters(ParameterHandler &prm);

    PressureAgglomeration(const FESystem<dim> &fe, const Mapping<dim> &mapping,
                          const ParticleSet<dim> &particles, const CutCellQuadrature<dim> &quadrature);

    bool enabled() const { return max_fluid_fraction > 0; }

    /// The tie of one agglomerated cell: its pressure DoFs, its neighbours' (the
    /// masters) and the matrix T with p_cell = T p_masters.
    struct Link
    {
      std::vector<types::global_dof_index> cell_dofs, masters;
      FullMatrix<double>                   T;
    };

    /// The links of the locally owned cells (none while disabled).
    std::vector<Link> links(const DoFHandler<dim> &dof_handler) const;

    /// Add the links as constraints where the cell's DoFs are not constrained yet.
    static void add_to(const std::vector<Link> &links, AffineConstraints<double> &constraints);

  private:
    const FESystem<dim> &         fe;
    const Mapping<dim> &          mapping;
    const ParticleSet<dim> &      particles;
    const CutCellQuadrature<dim> &quadrature;
    double                        max_fluid_fraction = 0;
  };
} // namespace fdparticle

#endif
