// `linkbox`: every process runs alone. In a build with MPI (LINKBOX_MPI_PROGRAM), a process that
// mpirun started becomes `linkbox-mpi` from this executable's folder (exec: the same process,
// arguments and environment), so that `mpirun -np N linkbox ...` runs as before while a plain
// run loads no MPI library.
#include "cli/run_mode.hpp"

#ifdef LINKBOX_MPI_PROGRAM
#include "distributed/launched.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>
#endif

namespace linkbox::cli {

#ifdef LINKBOX_MPI_PROGRAM
namespace {

// Never returns: exec replaces this process, and a failed one ends it as a failed MPI job does.
[[noreturn]] void become_mpi_program(char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string program = (self.parent_path() / LINKBOX_MPI_PROGRAM).string();
  if (!ec) execv(program.c_str(), argv);
  std::fprintf(stderr, "linkbox: started by mpirun, but %s could not start: %s\n", program.c_str(),
               ec ? ec.message().c_str() : std::strerror(errno));
  std::exit(3);
}

}  // namespace
#endif

std::unique_ptr<RunMode> start_run_mode(int* /*argc*/, [[maybe_unused]] char*** argv) {
#ifdef LINKBOX_MPI_PROGRAM
  if (distributed::launched()) become_mpi_program(*argv);
#endif
  return std::make_unique<RunMode>();
}

}  // namespace linkbox::cli
