#include <deal.II/base/exceptions.h>

#include <fdparticle/base/parameter_tools.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
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

    namespace
    {
      /// Edit distance between two names, case-insensitive (insertions, deletions,
      /// substitutions, and swaps of neighbours).
      unsigned int distance(const std::string &a, const std::string &b)
      {
        const auto lower = [](const char c) { return char(std::tolower(c)); };
        std::vector<std::vector<unsigned int>> d(a.size() + 1,
                                                 std::vector<unsigned int>(b.size() + 1));
        for (std::size_t i = 0; i <= a.size(); ++i)
          d[i][0] = i;
        for (std::size_t j = 0; j <= b.size(); ++j)
          d[0][j] = j;
        for (std::size_t i = 1; i <= a.size(); ++i)
          for (std::size_t j = 1; j <= b.size(); ++j)
            {
              const unsigned int cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
              d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
              if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
                  lower(a[i - 2]) == lower(b[j - 1]))
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        return d[a.size()][b.size()];
      }

      /// " Did you mean 'X'?" for the closest of the names, if it is close; else "".
      std::string suggestion(const std::string &name, const std::set<std::string> &names)
      {
        std::string  best;
        unsigned int best_distance = std::numeric_limits<unsigned int>::max();
        for (const std::string &candidate : names)
          if (const unsigned int d = distance(name, candidate); d < best_distance)
            {
              best          = candidate;
              best_distance = d;
            }
        return best_distance <= std::max<std::size_t>(2, name.size() / 3) ?
                 " Did you mean '" + best + "'?" :
                 "";
      }

      /// A subsection path as "A/B" ("" the top level).
      std::string joined(const std::vector<std::string> &path)
      {
        std::string p;
        for (const std::string &s : path)
          p += (p.empty() ? "" : "/") + s;
        return p;
      }

      /// The declared subsections and entries below each subsection path ("" the top,
      /// "A/B" a nested one), from prm's own listing.
      struct Declared
      {
        std::map<std::string, std::set<std::string>> subsections, entries;
      };

      /// The names of a map of Declared at a path (none if the path has none).
      const std::set<std::string> &names_at(const std::map<std::string, std::set<std::string>> &names,
                                           const std::string &                                  path)
      {
        static const std::set<std::string> none;
        const auto                         it = names.find(path);
        return it == names.end() ? none : it->second;
      }

      Declared declared_names(const ParameterHandler &prm)
      {
        std::ostringstream listing;
        prm.print_parameters(listing, ParameterHandler::OutputStyle(ParameterHandler::PRM | ParameterHandler::Short));
        Declared                 declared;
        std::vector<std::string> path;
        std::istringstream       in(listing.str());
        for (std::string line; std::getline(in, line);)
          {
            line = trim(line.substr(0, line.find('#')));
            if (line.rfind("subsection ", 0) == 0)
              {
                const std::string name = trim(line.substr(11));
                declared.subsections[joined(path)].insert(name);
                path.push_back(name);
              }
            else if (line == "end" && !path.empty())
              path.pop_back();
            else if (line.rfind("set ", 0) == 0)
              declared.entries[joined(path)].insert(trim(line.substr(4, line.find('=') - 4)));
          }
        return declared;
      }

      /// Runs of white space as one blank, as ParameterHandler reads names.
      std::string normalized(const std::string &name)
      {
        std::istringstream in(name);
        std::string        word, result;
        while (in >> word)
          result += (result.empty() ? "" : " ") + word;
        return result;
      }
    } // namespace

    void check_names(const ParameterHandler &prm, const std::string &text,
                     const std::string &file_name)
    {
      const Declared           declared = declared_names(prm);
      std::vector<std::string> path;
      std::istringstream       in(text);
      unsigned int             number = 0;
      std::string              pending;
      for (std::string line; std::getline(in, line);)
        {
          ++number;
          line = trim(line.substr(0, line.find('#')));
          // A line ending in a backslash continues on the next one.
          if (!line.empty() && line.back() == '\\')
            {
              pending += line.substr(0, line.size() - 1) + " ";
              continue;
            }
          line = trim(pending + line);
          pending.clear();
          const std::string here = joined(path);
          const std::string where = "Line " + std::to_string(number) + " of '" + file_name + "': ";
          const std::string in_what =
            here.empty() ? "at the top level" : "in subsection '" + here + "'";
          if (line.rfind("subsection ", 0) == 0)
            {
              const std::string name = normalized(line.substr(11));
              const auto       &known = names_at(declared.subsections, here);
              AssertThrow(known.count(name) > 0,
                          ExcMessage(where + "there is no subsection '" + name + "' " + in_what +
                                     "." + suggestion(name, known)));
              path.push_back(name);
            }
          else if (line == "end")
            {
              AssertThrow(!path.empty(),
                          ExcMessage(where + "'end' without a subsection to end."));
              path.pop_back();
            }
          else if (line.rfind("set ", 0) == 0 && line.find('=') != std::string::npos)
            {
              const std::string name = normalized(line.substr(4, line.find('=') - 4));
              const auto       &known = names_at(declared.entries, here);
              AssertThrow(known.count(name) > 0,
                          ExcMessage(where + "there is no entry '" + name + "' " + in_what +
                                     "." + suggestion(name, known)));
            }
        }
    }
  } // namespace ParameterTools
} // namespace fdparticle
