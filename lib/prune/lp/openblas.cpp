#include "prune/lp/openblas.hpp"

#include <dlfcn.h>

namespace linkbox::prune::lp {

// Every build of OpenBLAS (pthread, OpenMP, serial) exports this; the reference BLAS and
// LAPACK do not. RTLD_DEFAULT searches every library loaded with the process.
bool openblas_loaded() { return dlsym(RTLD_DEFAULT, "openblas_get_num_threads") != nullptr; }

}  // namespace linkbox::prune::lp
