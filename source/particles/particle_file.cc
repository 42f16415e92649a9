#include <deal.II/base/exceptions.h>

#include <fdparticle/base/parameter_tools.h>
#include <fdparticle/particles/particle_file.h>

#include <fstream>
#include <sstream>

namespace fdparticle
{
  namespace
  {
    /// Columns [begin, end) joined as a comma-separated vector, the form of a prm entry.
    std::string join(const std::vector<std::string> &columns, const std::size_t begin,
                     const std::size_t end)
    {
      std::string text;
      for (std::size_t c = begin; c < end; ++c)
        text += (c > begin ? ", " : "") + columns[c];
      return text;
    }

    bool starts_with_number(const std::string &text)
    {
      std::istringstream in(text);
      double             x;
      return static_cast<bool>(in >> x);
    }
  } // namespace

  template <int dim>
  std::string ParticleFile<dim>::line_form()
  {
    return std::string(dim == 2 ? "x, y" : "x, y, z") +
           ", radius or shape, density[, motion[, velocity[, angular velocity]]]";
  }

  template <int dim>
  std::vector<typename ParticleFile<dim>::Entry>
  ParticleFile<dim>::read(const std::string &filename, const MPI_Comm comm)
  {
    // Rank 0 reads; the text, or the reason why there is none, goes to every rank.
    std::pair<bool, std::string> content{false, ""};
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::ifstream in(filename);
        if (in)
          {
            std::ostringstream text;
            text << in.rdbuf();
            content = {true, text.str()};
          }
      }
    content = Utilities::MPI::broadcast(comm, content, 0);
    AssertThrow(content.first,
                ExcMessage("Parameter 'Particles/Particle file': cannot read '" + filename +
                           "' (a relative path starts in the directory fdparticle runs in)."));
    return parse(content.second, filename);
  }

  template <int dim>
  std::vector<typename ParticleFile<dim>::Entry>
  ParticleFile<dim>::parse(const std::string &text, const std::string &filename)
  {
    using namespace ParameterTools;
    const std::string form = line_form();
    std::vector<Entry> entries;
    std::istringstream in(text);
    std::string        line;
    bool               first_line = true;
    for (unsigned int number = 1; std::getline(in, line); ++number)
      {
        line = trim(line);
        if (line.empty() || line[0] == '#')
          continue;
        const bool header = first_line && !starts_with_number(line);
        first_line = false;
        if (header)
          continue;

        const std::string name = "Particles/Particle file (" + filename + ", line " +
                                 std::to_string(number) + ")";
        std::vector<std::string> columns = split(line, ',');
        // Empty trailing columns: a spreadsheet pads the short rows of free particles.
        while (!columns.empty() && columns.back().empty())
          columns.pop_back();
        const std::size_t velocity_begin = dim + 3, velocity_end = 2 * dim + 3;
        AssertThrow(columns.size() >= dim + 2 &&
                      (columns.size() <= velocity_begin || columns.size() >= velocity_end),
                    ExcMessage("Parameter '" + name + "': '" + line + "' has " +
                               std::to_string(columns.size()) + " columns; a line is '" +
                               form + "'."));
        // Where the motion goes (a word) a number: the file has a z column in a 2D scene.
        AssertThrow(dim == 3 || columns.size() <= dim + 2 || !starts_with_number(columns[dim + 2]),
                    ExcMessage("Parameter '" + name + "': '" + line + "' has a number where the "
                               "motion (free, fixed, prescribed) goes: is it a 3D particle file? "
                               "This scene is 2D; a line is '" + form + "'."));
        Entry entry{name, {join(columns, 0, dim), columns[dim], columns[dim + 1]}};
        if (columns.size() > dim + 2)
          entry.fields.push_back(columns[dim + 2]);
        if (columns.size() >= velocity_end)
          entry.fields.push_back(join(columns, velocity_begin, velocity_end));
        if (columns.size() > velocity_end)
          entry.fields.push_back(join(columns, velocity_end, columns.size()));
        entries.push_back(entry);
      }
    AssertThrow(!entries.empty(),
                ExcMessage("Parameter 'Particles/Particle file': '" + filename +
                           "' lists no particle; a line is '" + form + "'."));
    return entries;
  }

  template class ParticleFile<2>;
  template class ParticleFile<3>;
} // namespace fdparticle
