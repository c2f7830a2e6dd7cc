#pragma once
// CLP's LAPACK is whatever Debian's liblapack.so.3 alternative names: the reference LAPACK,
// or OpenBLAS, whose thread pool starts when the library loads and busy-waits for work for a
// while (papers/decisions/solve-driver.md). The CLI asks which, so that only OpenBLAS costs a
// restart with OPENBLAS_NUM_THREADS=1.
namespace linkbox::prune::lp {

// True when OpenBLAS is among the libraries loaded with the process.
bool openblas_loaded();

}  // namespace linkbox::prune::lp
