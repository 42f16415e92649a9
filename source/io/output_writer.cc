#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_out.h>

#include <fdparticle/base/blas_kernels.h>
#include <fdparticle/base/build_info.h>
#include <fdparticle/io/output_writer.h>
#include <fdparticle/particles/sphere.h>
#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/fem/introspection.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <iomanip>
#include <istream>
#include <ostream>

namespace fdparticle
{
  template <int dim>
  void OutputWriter<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    {
      prm.declare_entry("Directory", "output", Patterns::Anything(),
                        "Directory for all output; created if missing.");
      prm.declare_entry("VTU interval", "1", Patterns::Integer(0),
                        "Write ParaView field output every N steps (and at t = 0); 0: never.");
    }
    prm.leave_subsection();
  }

  template <int dim>
  void OutputWriter<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    output_directory = prm.get("Directory");
    vtu_interval = prm.get_integer("VTU interval");
    prm.leave_subsection();
    AssertThrow(!output_directory.empty(),
                ExcMessage("Parameter 'Output/Directory' must not be empty."));
  }

  namespace
  {
    using Columns = std::vector<std::pair<std::string, double>>;

    /// A tensor as three numbers: unused components (z in 2D) are 0.
    template <int d>
    std::array<double, 3> three(const Tensor<1, d> &t)
    {
      std::array<double, 3> a{{0, 0, 0}};
      for (int i = 0; i < std::min(3, d); ++i)
        a[i] = t[i];
      return a;
    }

    /// One row of particles.csv per particle: in 2D z, the in-plane ω and torque are 0. The
    /// radius comes last: random and file particles differ in size.
    template <int dim>
    Columns particle_columns(const double time, const Particle<dim> &P)
    {
      Columns columns{{"time", time}, {"id", double(P.id)}};
      const std::pair<std::string, std::array<double, 3>> vectors[] = {
        {"", three(P.position)},       {"v", three(P.velocity)}, {"w", three(P.omega)},
        {"f", three(P.force)},         {"t", three(P.torque)},
        {"contact_f", three(P.contact_force)},
        {"rot", three(RigidBody<dim>::rotation_vector(P.orientation))}};
      for (const auto &[prefix, values] : vectors)
        for (unsigned int d = 0; d < 3; ++d)
          columns.emplace_back(prefix + "xyz"[d], values[d]);
      columns.emplace_back("radius", P.bounding_radius());
      return columns;
    }

    /// The point data of a particle in the VTU files: scalars, vectors of dim components
    /// and the shape tensor Q S Qᵀ (dim × dim, the semi-axes turned: ParaView's Tensor
    /// Glyph with a sphere of radius 1 draws the particle). In 2D the angular velocity,
    /// torque and rotation are the z components.
    template <int dim>
    std::vector<std::pair<std::string, std::vector<double>>>
    particle_point_data(const Particle<dim> &P)
    {
      const Tensor<2, dim> Q = RigidBody<dim>::rotation_matrix(P.orientation);
      const Tensor<2, dim> shape = Q * P.shape->semi_axes_tensor() * transpose(Q);
      std::vector<double>  tensor;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          tensor.push_back(shape[i][j]);
      const auto vector = [](const Tensor<1, dim> &t) {
        std::vector<double> v(dim);
        for (unsigned int d = 0; d < dim; ++d)
          v[d] = t[d];
        return v;
      };
      // Axial vectors (ω, T, the rotation angle × axis) have one component in 2D.
      const auto axial = [](const Tensor<1, 3> &t) {
        return dim == 2 ? std::vector<double>{t[2]} : std::vector<double>{t[0], t[1], t[2]};
      };
      const Tensor<1, 3> rotation = RigidBody<dim>::rotation_vector(P.orientation);
      return {{"id", {double(P.id)}},
              {"radius", {P.bounding_radius()}},
              {"density", {P.density}},
              {"velocity", vector(P.velocity)},
              {"angular_velocity", axial(P.omega)},
              {"rotation", axial(rotation)},
              {"force", vector(P.force)},
              {"torque", axial(P.torque)},
              {"contact_force", vector(P.contact_force)},
              {"shape", tensor}};
    }

    /// One CSV line: the items, comma-separated.
    template <typename Items>
    void write_line(std::ostream &out, const Items &items)
    {
      bool first = true;
      for (const auto &item : items)
        {
          out << (first ? "" : ",") << item;
          first = false;
        }
      out << '\n';
    }

    void write_header(std::ostream &out, const Columns &columns)
    {
      std::vector<std::string> names;
      for (const auto &column : columns)
        names.push_back(column.first);
      write_line(out, names);
    }

    void write_row(std::ostream &out, const Columns &columns)
    {
      std::vector<double> values;
      for (const auto &column : columns)
        values.push_back(column.second);
      write_line(out, values);
    }

    /// Keep the header and the rows whose first field is at most 'last'; used on restart.
    void truncate_table(const std::string &file, const double last)
    {
      std::ifstream            in(file);
      std::vector<std::string> kept;
      std::string              line;
      while (std::getline(in, line))
        if (kept.empty() || std::stod(line.substr(0, line.find(','))) <=
                              last + 1e-9 * std::max(1.0, std::abs(last)))
          kept.push_back(line);
      in.close();
      std::ofstream out(file + ".tmp");
      for (const auto &l : kept)
        out << l << '\n';
      out.close();
      std::filesystem::rename(file + ".tmp", file);
    }
  } // namespace

  template <int dim>
  void OutputWriter<dim>::initialize(const ParameterHandler &prm,
                                     const StatisticsTable & statistics,
                                     const MPI_Comm communicator, const bool resume,
                                     const unsigned int resume_step, const double resume_time)
  {
    comm = communicator;
    root = (Utilities::MPI::this_mpi_process(comm) == 0);
    std::string error;
    if (root)
      {
        std::error_code ec;
        std::filesystem::create_directories(output_directory, ec);
        if (ec || !std::filesystem::is_directory(output_directory))
          error = "Output directory '" + output_directory + "' cannot be created" +
                  (ec ? " (" + ec.message() + ")." : ".");
        else if (resume)
          for (const std::string name : {"particles.csv", "statistics.csv"})
            if (!std::filesystem::exists(output_directory + "/" + name))
              error = "Cannot resume: '" + output_directory + "/" + name +
                      "' of the interrupted run is missing.";
      }
    error = Utilities::MPI::broadcast(comm, error, 0);
    // Every rank has it: end normally, not by MPI_Abort (main.cc).
    if (!error.empty())
      throw CollectiveError(error);
    if (!root)
      return;

    std::ofstream prm_out(output_directory + "/parameters.prm");
    prm_out << "# Written by " << build_description() << " on "
            << Utilities::MPI::n_mpi_processes(comm) << " MPI rank(s); BLAS: "
            << BlasKernels::description() << "\n";
    prm.print_parameters(prm_out, ParameterHandler::PRM);

    const std::string particles_file = output_directory + "/particles.csv";
    const std::string statistics_file = output_directory + "/statistics.csv";
    if (resume)
      {
        truncate_table(particles_file, resume_time);
        truncate_table(statistics_file, resume_step);
        particles_csv.open(particles_file, std::ios::app);
        statistics_csv.open(statistics_file, std::ios::app);
        return;
      }
    // A new run: the field files and the smoothness table of an earlier run into the same
    // directory would stand beside the new ones (or after them, if that run was longer).
    const std::regex earlier(
      R"((solution|particles)-[0-9]+(\.[0-9]+)?\.(vtu|pvtu)|(solution|particles)\.pvd|smoothness\.csv)");
    unsigned int removed = 0;
    for (const auto &entry : std::filesystem::directory_iterator(output_directory))
      if (entry.is_regular_file() &&
          std::regex_match(entry.path().filename().string(), earlier))
        removed += std::filesystem::remove(entry.path());
    if (removed > 0)
      std::cout << "fdparticle: removed " << removed << " field and table files of an earlier "
                << "run from '" << output_directory << "'" << std::endl;
    particles_csv.open(particles_file);
    Particle<dim> any;
    any.shape = std::make_shared<const Sphere<dim>>(1.0);
    write_header(particles_csv, particle_columns(0, any));
    statistics_csv.open(statistics_file);
    write_line(statistics_csv, statistics.names());
  }

  template <int dim>
  void OutputWriter<dim>::save(std::ostream &out) const
  {
    out << std::setprecision(17);
    for (const auto *records : {&solution_records, &particle_records})
      {
        out << records->size() << '\n';
        for (const auto &r : *records)
          out << r.first << ' ' << r.second << '\n';
      }
  }

  template <int dim>
  void OutputWriter<dim>::load(std::istream &in)
  {
    for (auto *records : {&solution_records, &particle_records})
      {
        std::size_t n = 0;
        in >> n;
        records->resize(n);
        for (auto &r : *records)
          in >> r.first >> r.second;
      }
  }

  template <int dim>
  void OutputWriter<dim>::write_particles_row(const double time, const ParticleSet<dim> &particles)
  {
    if (!root)
      return;
    particles_csv << std::setprecision(12);
    for (unsigned int k = 0; k < particles.size(); ++k)
      write_row(particles_csv, particle_columns(time, particles[k]));
    particles_csv.flush();
  }

  template <int dim>
  void OutputWriter<dim>::write_statistics_row(const StatisticsTable &statistics)
  {
    if (!root)
      return;
    statistics_csv << std::setprecision(10);
    write_line(statistics_csv, statistics.values());
    statistics_csv.flush();
  }

  template <int dim>
  void OutputWriter<dim>::write_fields(const unsigned int step, const double time,
                                       const Mapping<dim> &mapping,
                                       const DoFHandler<dim> &dof_handler,
                                       const TrilinosWrappers::MPI::Vector &solution,
                                       const Vector<float> &particle_fraction,
                                       const ParticleSet<dim> &particles)
  {
    const std::string counter = Utilities::int_to_string(step, 5);
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);

    std::vector<std::string> names(dim, "velocity");
    names.insert(names.end(), dim, "lambda");
    names.emplace_back("pressure");
    std::vector<DataComponentInterpretation::DataComponentInterpretation> interpretation(
      Introspection<dim>::pressure_component, DataComponentInterpretation::component_is_part_of_vector);
    interpretation.push_back(DataComponentInterpretation::component_is_scalar);

    DataOut<dim> data_out;
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(solution, names, DataOut<dim>::type_dof_data, interpretation);
    data_out.add_data_vector(particle_fraction, "particle_fraction");
    Vector<float> subdomain(dof_handler.get_triangulation().n_active_cells());
    subdomain = static_cast<float>(rank);
    data_out.add_data_vector(subdomain, "subdomain");
    data_out.build_patches(mapping, Introspection<dim>::output_subdivisions);

    const std::string piece = "solution-" + counter + "." + Utilities::int_to_string(rank, 4) + ".vtu";
    std::ofstream     out(output_directory + "/" + piece);
    data_out.write_vtu(out);

    if (!root)
      return;
    std::vector<std::string> pieces;
    for (unsigned int r = 0; r < n_ranks; ++r)
      pieces.push_back("solution-" + counter + "." + Utilities::int_to_string(r, 4) + ".vtu");
    const std::string pvtu = "solution-" + counter + ".pvtu";
    std::ofstream     pvtu_out(output_directory + "/" + pvtu);
    data_out.write_pvtu_record(pvtu_out, pieces);
    solution_records.emplace_back(time, pvtu);
    std::ofstream pvd(output_directory + "/solution.pvd");
    DataOutBase::write_pvd_record(pvd, solution_records);

    // One VTK point per particle (deal.II's point patches); ParaView draws spheres with a
    // glyph scaled by 'radius', any shape with a Tensor Glyph of 'shape'. VTU data is
    // single precision: exact values are in the CSV.
    std::vector<DataOutBase::Patch<0, dim>> patches(particles.size());
    std::vector<std::string>                point_names;
    std::vector<std::tuple<unsigned int, unsigned int, std::string,
                           DataComponentInterpretation::DataComponentInterpretation>>
      vectors;
    for (unsigned int k = 0; k < particles.size(); ++k)
      {
        const auto data = particle_point_data(particles[k]);
        patches[k].vertices[0] = particles[k].position;
        patches[k].patch_index = k;
        unsigned int n_values = 0;
        for (const auto &field : data)
          n_values += field.second.size();
        patches[k].data.reinit(n_values, 1);
        unsigned int row = 0;
        for (const auto &[name, values] : data)
          {
            if (k == 0)
              {
                if (values.size() > 1)
                  vectors.emplace_back(row, row + values.size() - 1, name,
                                       name == "shape" ?
                                         DataComponentInterpretation::component_is_part_of_tensor :
                                         DataComponentInterpretation::component_is_part_of_vector);
                point_names.insert(point_names.end(), values.size(), name);
              }
            for (const double v : values)
              patches[k].data(row++, 0) = v;
          }
      }
    const std::string particles_vtu = "particles-" + counter + ".vtu";
    std::ofstream     pout(output_directory + "/" + particles_vtu);
    DataOutBase::write_vtu(patches, point_names, vectors, DataOutBase::VtkFlags(time, step), pout);
    particle_records.emplace_back(time, particles_vtu);
    std::ofstream ppvd(output_directory + "/particles.pvd");
    DataOutBase::write_pvd_record(ppvd, particle_records);
  }

  template class OutputWriter<2>;
  template class OutputWriter<3>;
} // namespace fdparticle
