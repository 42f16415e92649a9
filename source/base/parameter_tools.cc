#include <deal.II/base/exceptions.h>

#include <fdparticle/base/parameter_tools.h>

#include <cctype>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace fdparticle
{
  namespace ParameterTools
  {
    std::string trim(const std::string &text)
    {
      const auto begin = text.find_first_not_of(" \t\n\r");
      if (begin == std::string::npos)
        return "";
      const auto end = text.find_last_not_of(" \t\n\r");
      return text.substr(begin, end - begin + 1);
    }

    std::vector<std::string> split(const std::string &text, const char separator)
    {
      std::vector<std::string> pieces;
      std::string              piece;
      std::istringstream       in(text);
      while (std::getline(in, piece, separator))
        pieces.push_back(trim(piece));
      if (!text.empty() && text.back() == separator)
        pieces.emplace_back("");
      return pieces;
    }

    double to_double(const std::string &text, const std::string &entry)
    {
      const std::string t = trim(text);
      std::size_t       used = 0;
      double            value = 0;
      bool              ok = !t.empty();
      if (ok)
        try
          {
            value = std::stod(t, &used);
          }
        catch (...)
          {
            ok = false;
          }
      AssertThrow(ok && used == t.size() && std::isfinite(value),
                  ExcMessage("Parameter '" + entry + "': '" + t +
                             "' is not a finite number."));
      return value;
    }

    double get_non_negative(const ParameterHandler &prm, const std::string &name,
                            const std::string &entry_path)
    {
      const double value = to_double(prm.get(name), entry_path);
      AssertThrow(value >= 0,
                  ExcMessage("Parameter '" + entry_path + "' must not be negative, got " +
                             prm.get(name) + "."));
      return value;
    }

    std::optional<double> get_auto_or_number(const ParameterHandler &prm,
                                             const std::string &name,
                                             const std::string &entry_path,
                                             const Zero zero)
    {
      const std::string text = trim(prm.get(name));
      if (text == "auto")
        return {};
      const double value = to_double(text, entry_path);
      AssertThrow(zero == Zero::allowed ? value >= 0 : value > 0,
                  ExcMessage("Parameter '" + entry_path + "' must be " +
                             (zero == Zero::allowed ? "zero or positive" : "positive") +
                             " or 'auto', got " + text + "."));
      return value;
    }

    template <int dim>
    Tensor<1, dim> to_tensor(const std::string &text, const std::string &entry)
    {
      const std::vector<std::string> pieces = split(text, ',');
      AssertThrow(pieces.size() == dim,
                  ExcMessage("Parameter '" + entry + "' needs " +
                             (dim == 1 ? std::string("1 number") :
                                         std::to_string(dim) + " comma-separated numbers") +
                             (dim == 1 ? std::string(" (in 2D an angular velocity is w_z alone)") :
                                         " (Dimension = " + std::to_string(dim) + ")") +
                             ", got '" + trim(text) + "'."));
      Tensor<1, dim> t;
      for (unsigned int d = 0; d < dim; ++d)
        t[d] = to_double(pieces[d], entry);
      return t;
    }

    template <int dim>
    Tensor<1, dim> get_tensor(const ParameterHandler &prm, const std::string &name,
                              const std::string &entry_path)
    {
      return to_tensor<dim>(prm.get(name), entry_path);
    }

    std::string format_short(const double x)
    {
      std::ostringstream s;
      s << std::setprecision(3) << x;
      return s.str();
    }

    std::string one_line_message(const std::exception &exc)
    {
      std::string message = exc.what();
      // deal.II exceptions carry a framed report: the user's sentence follows this marker
      // and ends at the stack trace or the closing line of dashes.
      const std::string marker = "Additional information:";
      const auto        pos = message.find(marker);
      if (pos != std::string::npos)
        {
          message = message.substr(pos + marker.size());
          for (const std::string end : {"\nStacktrace:", "\n-----"})
            {
              const auto cut = message.find(end);
              if (cut != std::string::npos)
                message = message.substr(0, cut);
            }
        }
      std::string line;
      bool        space = false;
      for (const char c : message)
        if (std::isspace(static_cast<unsigned char>(c)))
          space = !line.empty();
        else
          {
            if (space)
              line += ' ';
            line += c;
            space = false;
          }
      return line;
    }

    template Tensor<1, 1> to_tensor<1>(const std::string &, const std::string &);
    template Tensor<1, 2> to_tensor<2>(const std::string &, const std::string &);
    template Tensor<1, 3> to_tensor<3>(const std::string &, const std::string &);
    template Tensor<1, 2> get_tensor<2>(const ParameterHandler &, const std::string &,
                                        const std::string &);
    template Tensor<1, 3> get_tensor<3>(const ParameterHandler &, const std::string &,
                                        const std::string &);
  } // namespace ParameterTools
} // namespace fdparticle
