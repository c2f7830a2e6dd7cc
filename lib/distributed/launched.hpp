#pragma once
// Whether mpirun (or another launcher) started this process, read from the environment the
// launcher sets. It needs no MPI library, so the plain `linkbox` can ask it before handing a
// launched process over to `linkbox-mpi` (cli/run_local.cpp).
#include <cstdlib>

namespace linkbox::distributed {

inline bool launched() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

}  // namespace linkbox::distributed
