#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <fdparticle/base/blas_kernels.h>
#include <fdparticle/base/build_info.h>
#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/core/simulation.h>

#include <fstream>
#include <iostream>
#include <sstream>

namespace
{
  void print_usage(std::ostream &out)
  {
    out << "Usage: fdparticle [--help] [--version] [--print-parameters] FILE.prm\n"
           "  Simulates incompressible flow with freely moving rigid particles by the\n"
           "  fictitious-domain / distributed-Lagrange-multiplier method.\n"
           "  FILE.prm            the scene (deal.II parameter file); see prm/ for examples\n"
           "  --print-parameters  print every parameter with its default and documentation\n"
           "  --version           print which build this is (source revision, deal.II, BLAS)\n"
           "  --help              print this text\n"
           "  Run in parallel with: mpirun -np N fdparticle FILE.prm\n";
  }

  /// Input errors surface in the constructor, on every rank alike, and end the program
  /// normally. An error during the run may hit one rank only: then abort all of them,
  /// or the others would wait for it forever.
  template <int dim>
  void run_scene(dealii::ParameterHandler &prm, const MPI_Comm comm)
  {
    using namespace dealii;
    fdparticle::Simulation<dim> simulation(prm, comm);
    try
      {
        simulation.run();
      }
    catch (fdparticle::CollectiveError &)
      {
        throw; // every rank has it: end normally, rank 0 prints it
      }
    catch (std::exception &exc)
      {
        if (Utilities::MPI::n_mpi_processes(comm) == 1)
          throw;
        std::cerr << "fdparticle: error on rank " << Utilities::MPI::this_mpi_process(comm) << ": "
                  << fdparticle::ParameterTools::one_line_message(exc) << std::endl;
        MPI_Abort(comm, 1);
      }
  }
} // namespace

int main(int argc, char **argv)
{
  using namespace dealii;
  using namespace fdparticle;
  BlasKernels::select_for_this_cpu(argv);
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const bool                       root = Utilities::MPI::this_mpi_process(comm) == 0;

  try
    {
      ParameterHandler prm;
      declare_all_parameters(prm);

      std::string file;
      for (int i = 1; i < argc; ++i)
        {
          const std::string arg = argv[i];
          if (arg == "--help" || arg == "-h")
            {
              if (root)
                print_usage(std::cout);
              return 0;
            }
          if (arg == "--version")
            {
              if (root)
                std::cout << build_description() << "\nBLAS: " << BlasKernels::description()
                          << std::endl;
              return 0;
            }
          if (arg == "--print-parameters")
            {
              if (root)
                prm.print_parameters(std::cout, ParameterHandler::PRM);
              return 0;
            }
          AssertThrow(arg.empty() || arg[0] != '-',
                      ExcMessage("Unknown option '" + arg + "'; see fdparticle --help."));
          AssertThrow(file.empty(), ExcMessage("Give exactly one parameter file; see --help."));
          file = arg;
        }
      AssertThrow(!file.empty(), ExcMessage("No parameter file given; see fdparticle --help."));
      AssertThrow(std::ifstream(file).good(),
                  ExcMessage("Cannot read parameter file '" + file + "'."));
      {
        std::ifstream      in(file);
        std::ostringstream text;
        text << in.rdbuf();
        ParameterTools::check_names(prm, text.str(), file);
      }
      prm.parse_input(file, "", false, false);

      const int dim = prm.get_integer("Dimension");
      if (dim == 2)
        run_scene<2>(prm, comm);
      else
        run_scene<3>(prm, comm);
    }
  catch (std::exception &exc)
    {
      if (root)
        std::cerr << "fdparticle: error: " << ParameterTools::one_line_message(exc) << std::endl;
      return 1;
    }
  catch (...)
    {
      if (root)
        std::cerr << "fdparticle: error: unknown exception" << std::endl;
      return 1;
    }
  return 0;
}
