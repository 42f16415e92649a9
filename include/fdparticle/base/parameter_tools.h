#ifndef fdparticle_base_parameter_tools_h
#define fdparticle_base_parameter_tools_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fdparticle
{
  using namespace dealii;

  /**
   * An error that every MPI rank detects alike and throws together (a run that cannot be
   * continued, a checkpoint that does not fit the scene): the program then ends normally
   * with a one-line message instead of aborting MPI.
   */
  class CollectiveError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * Parsing helpers shared by the classes that read parameters. Every error names the
   * entry (e.g. "Geometry/Lower corner") and says what was expected, in one sentence.
   */
  namespace ParameterTools
  {
    /// Split at a separator, trimming white space; empty pieces are kept.
    std::vector<std::string> split(const std::string &text, const char separator);

    /// Strip leading and trailing white space.
    std::string trim(const std::string &text);

    /// A real number; 'entry' names the parameter in the error message.
    double to_double(const std::string &text, const std::string &entry);

    /// The real number 'name' of the current subsection of prm, which must be >= 0;
    /// 'entry_path' (Subsection/Name) names it in the error message.
    double get_non_negative(const ParameterHandler &prm, const std::string &name,
                            const std::string &entry_path);

    /// Whether a number read by get_auto_or_number may be zero.
    enum class Zero
    {
      allowed,
      refused
    };

    /// The entry 'name' of the current subsection of prm: 'auto' (an empty optional: the
    /// reading class computes the value) or a number > 0 (>= 0 if zero is allowed).
    std::optional<double> get_auto_or_number(const ParameterHandler &prm,
                                             const std::string &name,
                                             const std::string &entry_path,
                                             const Zero zero);

    /// A comma-separated vector of exactly dim numbers.
    template <int dim>
    Tensor<1, dim> to_tensor(const std::string &text, const std::string &entry);

    /// Same, read from the current subsection of prm.
    template <int dim>
    Tensor<1, dim> get_tensor(const ParameterHandler &prm, const std::string &name,
                              const std::string &entry_path);

    /// A number for a message, to 3 significant digits ("2e+11", "0.05").
    std::string format_short(const double x);

    /**
     * Check that every subsection and entry the text of a parameter file names is declared
     * in prm, before ParameterHandler reads it: a name it does not know is refused with the
     * line, the subsection it was looked for in, and the declared name closest to it
     * ("did you mean ..."). file_name is for the message.
     */
    void check_names(const ParameterHandler &prm, const std::string &text,
                     const std::string &file_name);

    /// The first line of the message of a deal.II or standard exception, made into one line.
    std::string one_line_message(const std::exception &exc);
  } // namespace ParameterTools
} // namespace fdparticle

#endif
