#include <fdparticle/base/blas_kernels.h>

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <sstream>

namespace fdparticle
{
  namespace BlasKernels
  {
    namespace
    {
      /// Set for the restarted program: the kernels OpenBLAS had chosen itself.
      constexpr const char *fallback_variable = "FDPARTICLE_OPENBLAS_FALLBACK";

      /// OpenBLAS's own name of a string it reports, or "" where the BLAS loaded is not
      /// OpenBLAS (looked up at run time: libblas.so.3 may be any BLAS).
      std::string openblas_string(const char *function)
      {
        using Function = char *(*)();
        const auto f = reinterpret_cast<Function>(dlsym(RTLD_DEFAULT, function));
        const char *s = f ? f() : nullptr;
        return s ? std::string(s) : std::string();
      }

      /// The kernels for this CPU's widest vector instructions OpenBLAS has, or "".
      std::string kernels_for_this_cpu()
      {
        __builtin_cpu_init();
        if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
            __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
            __builtin_cpu_supports("avx512vl"))
          return "SkylakeX";
        if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
          return "Haswell";
        return "";
      }
    } // namespace

    void select_for_this_cpu(char **argv)
    {
      if (std::getenv("OPENBLAS_CORETYPE") != nullptr)
        return;
      const std::string chosen = openblas_string("openblas_get_corename");
      if (chosen != "Prescott")
        return;
      const std::string wanted = kernels_for_this_cpu();
      if (wanted.empty())
        return;
      setenv("OPENBLAS_CORETYPE", wanted.c_str(), 1);
      setenv(fallback_variable, chosen.c_str(), 1);
      execv("/proc/self/exe", argv);
      // Not restarted: go on as OpenBLAS chose.
      unsetenv("OPENBLAS_CORETYPE");
      unsetenv(fallback_variable);
    }

    std::string description()
    {
      const std::string config = openblas_string("openblas_get_config");
      if (config.empty())
        return "not OpenBLAS";
      // "OpenBLAS 0.3.21 DYNAMIC_ARCH NO_AFFINITY Prescott MAX_THREADS=64": its first two
      // words.
      std::istringstream words(config);
      std::string         name, version;
      words >> name >> version;
      std::string text = name + " " + version + ", " +
                         openblas_string("openblas_get_corename") + " kernels";
      if (const char *fallback = std::getenv(fallback_variable))
        text += std::string(" (chosen by fdparticle: OpenBLAS took this CPU for a ") +
                fallback + ")";
      else if (std::getenv("OPENBLAS_CORETYPE") != nullptr)
        text += " (OPENBLAS_CORETYPE)";
      return text;
    }
  } // namespace BlasKernels
} // namespace fdparticle
