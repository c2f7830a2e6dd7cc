// A build without MPI (LINKBOX_MPI off): every process runs alone.
#include "cli/run_mode.hpp"

namespace linkbox::cli {

std::unique_ptr<RunMode> start_run_mode(int* /*argc*/, char*** /*argv*/) { return std::make_unique<RunMode>(); }

}  // namespace linkbox::cli
