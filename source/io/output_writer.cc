#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_out.h>

#include <fdparticle/io/output_writer.h>
#include <fdparticle/core/parameter_tools.h>

#include <filesystem>
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
  void OutputWriter<dim>::initialize(const ParameterHandler &prm, const MPI_Comm communicator,
                                     const bool resume, const unsigned int resume_step,
                                     const double resume_time)
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
    particles_csv.open(particles_file);
    particles_csv << "time,id,x,y,z,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz,"
                     "contact_fx,contact_fy,contact_fz\n";
    statistics_csv.open(statistics_file);
    statistics_csv << "step,time,dt,cells,dofs,nonlinear_iterations,residual,wall_seconds,"
                      "initial_residual,max_velocity,hydrostatic_deviation,coarse_cut_cells,"
                      "time_step_reductions,mean_vx,mean_vy,mean_vz\n";
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
      {
        const Particle<dim> &P = particles[k];
        // Unused components (z in 2D, in-plane ω and torque) are written as 0.
        auto three = [](const auto &t) {
          std::array<double, 3> a{{0, 0, 0}};
          for (unsigned int d = 0; d < std::min<unsigned int>(3, t.dimension); ++d)
            a[d] = t[d];
          return a;
        };
        particles_csv << time << ',' << P.id;
        for (const auto &v : {three(P.position), three(P.velocity), three(P.omega),
                              three(P.force), three(P.torque), three(P.contact_force)})
          for (const double x : v)
            particles_csv << ',' << x;
        particles_csv << '\n';
      }
    particles_csv.flush();
  }

  template <int dim>
  void OutputWriter<dim>::write_statistics_row(const StepStatistics &s)
  {
    if (!root)
      return;
    statistics_csv << std::setprecision(10) << s.step << ',' << s.time << ',' << s.dt << ','
                   << s.cells << ',' << s.dofs << ',' << s.nonlinear_iterations << ','
                   << s.residual << ',' << s.wall_seconds << ',' << s.initial_residual << ','
                   << s.max_velocity << ',' << s.hydrostatic_deviation << ','
                   << s.coarse_cut_cells << ',' << s.time_step_reductions << ','
                   << s.mean_velocity[0] << ',' << s.mean_velocity[1] << ','
                   << s.mean_velocity[2] << '\n';
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
      2 * dim, DataComponentInterpretation::component_is_part_of_vector);
    interpretation.push_back(DataComponentInterpretation::component_is_scalar);

    DataOut<dim> data_out;
    data_out.attach_dof_handler(dof_handler);
    data_out.add_data_vector(solution, names, DataOut<dim>::type_dof_data, interpretation);
    data_out.add_data_vector(particle_fraction, "particle_fraction");
    Vector<float> subdomain(dof_handler.get_triangulation().n_active_cells());
    subdomain = static_cast<float>(rank);
    data_out.add_data_vector(subdomain, "subdomain");
    data_out.build_patches(mapping, 2);

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

    // One VTK point per particle; ParaView draws spheres with a glyph scaled by 'radius'.
    const std::string particles_vtu = "particles-" + counter + ".vtu";
    std::ofstream     pout(output_directory + "/" + particles_vtu);
    const unsigned int np = particles.size();
    pout << std::setprecision(12)
         << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
         << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << np
         << "\">\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (unsigned int k = 0; k < np; ++k)
      {
        for (unsigned int d = 0; d < 3; ++d)
          pout << (d < dim ? particles[k].position[d] : 0.0) << ' ';
        pout << '\n';
      }
    pout << "</DataArray>\n</Points>\n<Cells>\n"
         << "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
    for (unsigned int k = 0; k < np; ++k)
      pout << k << ' ';
    pout << "\n</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
    for (unsigned int k = 0; k < np; ++k)
      pout << k + 1 << ' ';
    pout << "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (unsigned int k = 0; k < np; ++k)
      pout << "1 ";
    pout << "\n</DataArray>\n</Cells>\n<PointData Scalars=\"radius\">\n";
    auto array = [&](const std::string &name, const unsigned int n_comp, auto value) {
      pout << "<DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\""
           << n_comp << "\" format=\"ascii\">\n";
      for (unsigned int k = 0; k < np; ++k)
        {
          for (unsigned int c = 0; c < n_comp; ++c)
            pout << value(particles[k], c) << ' ';
          pout << '\n';
        }
      pout << "</DataArray>\n";
    };
    array("id", 1, [](const Particle<dim> &P, unsigned int) { return double(P.id); });
    array("radius", 1, [](const Particle<dim> &P, unsigned int) { return P.radius; });
    array("density", 1, [](const Particle<dim> &P, unsigned int) { return P.density; });
    array("velocity", 3, [](const Particle<dim> &P, unsigned int c) {
      return c < dim ? P.velocity[c] : 0.0;
    });
    array("angular_velocity", 3, [](const Particle<dim> &P, unsigned int c) { return P.omega[c]; });
    array("orientation", 4, [](const Particle<dim> &P, unsigned int c) {
      return P.orientation.coeffs()[(c + 3) % 4]; // w, x, y, z
    });
    array("force", 3, [](const Particle<dim> &P, unsigned int c) {
      return c < dim ? P.force[c] : 0.0;
    });
    array("torque", 3, [](const Particle<dim> &P, unsigned int c) { return P.torque[c]; });
    pout << "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    particle_records.emplace_back(time, particles_vtu);
    std::ofstream ppvd(output_directory + "/particles.pvd");
    DataOutBase::write_pvd_record(ppvd, particle_records);
  }

  template class OutputWriter<2>;
  template class OutputWriter<3>;
} // namespace fdparticle
