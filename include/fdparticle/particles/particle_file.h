#ifndef fdparticle_particles_particle_file_h
#define fdparticle_particles_particle_file_h

#include <deal.II/base/mpi.h>

#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * A list of particles in a CSV file (Particles/Particle file), for scenes with more
   * particles than a parameter string holds. One particle per line:
   *
   *   x, y[, z], radius, density[, motion[, vx, vy[, vz][, angular velocity]]]
   *
   * where the radius may be a shape with its numbers separated by spaces, as
   * 'ellipse 0.2 0.1 30' or 'ellipsoid 0.2 0.1 0.1 0 0 1 45' (Particles/Particles),
   * with motion free (default), fixed or prescribed (then the velocity and optionally the
   * angular velocity follow, as in Particles/Particles). Lines starting with '#' and blank
   * lines are skipped, and so is a first line that starts with a name (a header such as
   * "x,y,z,radius,density"). The file is read on rank 0 and its text broadcast, so a
   * parallel run opens it once and every rank parses the same text and finds the same
   * errors.
   */
  template <int dim>
  class ParticleFile
  {
  public:
    /// One particle's line, split into the fields of a Particles/Particles entry:
    /// centre, radius, density[, motion[, velocity[, angular velocity]]].
    struct Entry
    {
      /// "Particles/Particle file (NAME, line N)", for error messages.
      std::string              name;
      std::vector<std::string> fields;
    };

    /// The entries of the file, in the order of its lines. Throws one-line errors that
    /// name the file and the line (the same on every rank).
    static std::vector<Entry> read(const std::string &filename, const MPI_Comm comm);

    /// "x, y[, z], radius, density[, motion[, velocity[, angular velocity]]]" for dim.
    static std::string line_form();

    /// The same from the file's text (the part that runs on every rank).
    static std::vector<Entry> parse(const std::string &text, const std::string &filename);
  };
} // namespace fdparticle

#endif
