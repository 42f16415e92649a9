#ifndef fdparticle_base_blas_kernels_h
#define fdparticle_base_blas_kernels_h

#include <string>

namespace fdparticle
{
  /**
   * The kernels of the BLAS that MUMPS's dense frontal matrices and the cell-matrix
   * assembly run on. OpenBLAS picks its kernels for the CPU when it is loaded; a CPU it
   * does not know (a processor newer than the library) gets its oldest ones, "Prescott"
   * (SSE3), which multiply dense matrices four to six times slower than its AVX2 or
   * AVX-512 ones on such a CPU (doc/performance.md, "The BLAS kernels").
   */
  namespace BlasKernels
  {
    /// If OpenBLAS fell back to its Prescott kernels on a CPU with AVX-512 (or AVX2 and
    /// FMA), start this program anew, the same arguments and environment, with
    /// OPENBLAS_CORETYPE naming the kernels for that instruction set (SkylakeX, Haswell):
    /// OpenBLAS reads it only when it is loaded. A user's OPENBLAS_CORETYPE is left as it
    /// is. Call first in main(), before MPI is initialized; if the restart fails, the
    /// program goes on with the kernels it has.
    void select_for_this_cpu(char **argv);

    /// Which BLAS and kernels run, for `fdparticle --version` and the head of
    /// parameters.prm: "OpenBLAS 0.3.21, SkylakeX kernels (chosen by fdparticle: OpenBLAS
    /// took this CPU for a Prescott)", or "not OpenBLAS".
    std::string description();
  } // namespace BlasKernels
} // namespace fdparticle

#endif
