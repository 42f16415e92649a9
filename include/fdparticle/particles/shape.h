#ifndef fdparticle_particles_shape_h
#define fdparticle_particles_shape_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/function.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>

namespace fdparticle
{
  using namespace dealii;

  /**
   * The geometry of a rigid particle about its centre, in the particle's frame: what the
   * cut-cell rules, the refinement band, the cell list, the particle equations and the
   * contact models ask of a particle's shape. Offsets r are body-frame offsets: x − X to
   * the nearest periodic image, turned back by the particle's rotation Q
   * (Particle::body_offset; a shape that is_isotropic() gets x − X unturned). A new shape
   * derives from this class and is created where particles are read (ParticleSet); the
   * rest of the code asks these questions only.
   *
   * Lubrication sees every particle as its bounding ball (and is refused for others than
   * balls); the contacts ask for support points.
   */
  template <int dim>
  class Shape
  {
  public:
    virtual ~Shape() = default;

    /// Points closer to the surface than this fraction of the size count as on it. A
    /// mesh vertex that lies on the surface in exact arithmetic (a centre on a vertex and
    /// a radius of whole cells, as scenes are often set up) falls on either side by
    /// round-off, and differently from its mirror image: cells would become cut or not
    /// (penalties, multiplier DoFs) at random, and a sphere on the axis of a symmetric
    /// box would drift sideways (tests/symmetry_vertex_3d.prm). Far above round-off
    /// (10⁻¹⁶), far below anything a mesh resolves.
    static constexpr double surface_tolerance = 1e-10;

    /// The shape's name as the parameter files and messages spell it.
    virtual std::string name() const = 0;

    /// Whether every rotation leaves the shape unchanged (a ball): its orientation then
    /// never enters the geometry, and offsets are not turned into the body frame.
    virtual bool is_isotropic() const = 0;

    /// Radius of the smallest ball about the centre that holds the shape: how far from
    /// the centre a cell, a bin or a wall must be to be sure to miss it.
    virtual double bounding_radius() const = 0;
    /// Radius of the largest ball about the centre that the shape holds: a box within it
    /// lies inside the shape.
    virtual double inscribed_radius() const = 0;

    /// The semi-axes along the body axes as a diagonal tensor (R I for a ball): what
    /// ParaView's Tensor Glyph draws, turned to the world as Q S Qᵀ.
    virtual Tensor<2, dim> semi_axes_tensor() const = 0;

    /// |P|: area (2D) or volume (3D).
    virtual double volume() const = 0;
    /// J/ρ in the body frame: the inertia tensor per unit density about the centre
    /// (doc/method.md §0 (F5)); in 2D only the zz entry is used.
    virtual Tensor<2, 3> inertia() const = 0;

    /// Whether the point at body offset r lies in the shape, its surface included within
    /// surface_tolerance.
    virtual bool contains(const Tensor<1, dim> &r) const = 0;
    /// The point of the shape farthest along the body direction n (|n| = 1), as a body
    /// offset: where a wall or another particle normal to n touches it (contacts).
    virtual Tensor<1, dim> support_point(const Tensor<1, dim> &n) const = 0;

    /// Signed distance from the point at body offset r to the surface along the ray from
    /// the centre (the distance itself for a ball), negative inside: which of several
    /// surfaces a point is nearest to.
    virtual double surface_distance(const Tensor<1, dim> &r) const = 0;

    /// Whether the shape, centred at X and turned by Q (body to world), meets the box by
    /// more than touching. Called only for boxes within the bounding ball.
    virtual bool meets(const BoundingBox<dim> &box, const Point<dim> &X,
                       const Tensor<2, dim> &Q) const = 0;

    /// A smooth level set of the shape centred at X and turned by Q, negative inside and
    /// zero on the surface, with gradient and Hessian (the level-set cut-cell rules,
    /// doc/method.md §7).
    virtual std::unique_ptr<Function<dim>> level_set(const Point<dim> &X,
                                                     const Tensor<2, dim> &Q) const = 0;

    /// Whether the level set's surface is a graph over the box in some coordinate
    /// direction, with the level set's derivative in that direction at least
    /// min_slope times its gradient's largest norm on the box (Saye's height direction,
    /// doc/method.md §7).
    virtual bool has_height_direction(const BoundingBox<dim> &box, const Point<dim> &X,
                                      const Tensor<2, dim> &Q, const double min_slope) const = 0;
  };
} // namespace fdparticle

#endif
