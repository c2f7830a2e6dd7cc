// `linkbox-mpi` (built with LINKBOX_MPI): under mpirun, the process is one rank of the job
// (distributed/); started otherwise, it runs alone. `linkbox` hands mpirun's processes to it.
#include "cli/interrupts.hpp"
#include "cli/run_mode.hpp"
#include "distributed/launched.hpp"
#include "distributed/mpi_solve.hpp"
#include "distributed/mpi_verify.hpp"

#include <cstdio>
#include <exception>
#include <string>

namespace linkbox::cli {

namespace {

class MpiMode final : public RunMode {
 public:
  MpiMode(int* argc, char*** argv) : world_(argc, argv) {}
  bool distributed() const override { return world_.size() > 1; }
  bool speaks() const override { return world_.rank() == 0; }

  int solve(const SolveCommand& cmd, const formulate::LoadedCase& c) const override {
    if (!distributed()) return RunMode::solve(cmd, c);
    distributed::Figures figures;
    const auto r = distributed::solve_distributed(*c.formulation, cmd.options, world_, &figures);
    if (!r) {  // a worker: rank 0 reports
      if (!cmd.no_verify) distributed::verify_distributed(*c.formulation, nullptr, verify_options(cmd), world_, nullptr);
      return interrupt_exit_code();
    }
    return report(
        cmd, c, *r, [&] { return nlohmann::json{{"distributed", figures.json()}}; },
        [&](bool verifying, const verify::VerifyOptions& vo) {
          return distributed::verify_distributed(*c.formulation, verifying ? &*r : nullptr, vo, world_, &figures);
        });
  }

  int internal_error() const override {
    try {
      throw;
    } catch (const distributed::Failed& e) {  // from another rank's search, worded as the CLI words it
      std::fprintf(stderr, "%s\n", e.what());
      return e.code;
    } catch (const distributed::Ended& e) {
      return e.code;
    } catch (const std::exception& e) {
      // An error of this rank alone: the others would wait for it until their timeout.
      if (distributed()) world_.fail(std::string("internal error: ") + e.what(), 1);
      return RunMode::internal_error();
    }
  }

 private:
  distributed::World world_;  // started when mpirun launched this process (distributed/wire.hpp)
};

}  // namespace

std::unique_ptr<RunMode> start_run_mode(int* argc, char*** argv) {
  if (!distributed::launched()) return std::make_unique<RunMode>();
  return std::make_unique<MpiMode>(argc, argv);
}

}  // namespace linkbox::cli
