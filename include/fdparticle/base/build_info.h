#ifndef fdparticle_base_build_info_h
#define fdparticle_base_build_info_h

#include <string>

namespace fdparticle
{
  /// Which build is running, for `fdparticle --version` and the head of parameters.prm:
  /// "fdparticle REVISION (deal.II VERSION, Release|Debug)", REVISION from git describe
  /// at build time (with "-dirty" for uncommitted changes).
  std::string build_description();
} // namespace fdparticle

#endif
