#include <deal.II/base/exceptions.h>

#include <fdparticle/base/statistics_table.h>

#include <algorithm>

namespace fdparticle
{
  void StatisticsTable::declare(const std::string &name)
  {
    AssertThrow(std::find(column_names.begin(), column_names.end(), name) == column_names.end(),
                ExcMessage("The statistics column '" + name + "' is declared twice."));
    column_names.push_back(name);
    row.push_back(0);
  }

  void StatisticsTable::declare_vector(const std::string &name)
  {
    for (const char c : {'x', 'y', 'z'})
      declare(name + c);
  }

  void StatisticsTable::new_row()
  {
    std::fill(row.begin(), row.end(), 0.0);
  }

  unsigned int StatisticsTable::index(const std::string &name) const
  {
    const auto it = std::find(column_names.begin(), column_names.end(), name);
    AssertThrow(it != column_names.end(),
                ExcMessage("The statistics column '" + name + "' was not declared."));
    return it - column_names.begin();
  }

  void StatisticsTable::set(const std::string &name, const double value)
  {
    row[index(name)] = value;
  }

  double StatisticsTable::get(const std::string &name) const
  {
    return row[index(name)];
  }
} // namespace fdparticle
