#include <deal.II/base/config.h>

#include <fdparticle/base/build_info.h>

#include <fdparticle_revision.h>

namespace fdparticle
{
  std::string build_description()
  {
#ifdef DEBUG
    const std::string type = "Debug";
#else
    const std::string type = "Release";
#endif
    return std::string("fdparticle ") + FDPARTICLE_REVISION + " (deal.II " +
           DEAL_II_PACKAGE_VERSION + ", " + type + ")";
  }
} // namespace fdparticle
