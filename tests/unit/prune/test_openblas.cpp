// Which LAPACK the process loaded: the answer the CLI restarts on, against the kernel's map.
#include "prune/lp/openblas.hpp"

#include <catch2/catch.hpp>

#include <dlfcn.h>
#include <fstream>
#include <string>

namespace {

// The process's mapped files, read by the kernel: a check independent of the dynamic linker.
bool mapped_file_mentions(const std::string& word) {
  std::ifstream maps("/proc/self/maps");
  for (std::string line; std::getline(maps, line);)
    if (line.find(word) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("OpenBLAS is reported loaded exactly when its library is mapped") {
  // The test binary loads CLP and through it LAPACK, as the CLI does.
  REQUIRE(mapped_file_mentions("libClp"));
  CHECK(linkbox::prune::lp::openblas_loaded() == mapped_file_mentions("openblas"));
}

TEST_CASE("a symbol lookup over the process finds the libraries loaded with it") {
  // The mechanism openblas_loaded relies on: CLP is a dependency, not linked into the binary.
  CHECK(dlsym(RTLD_DEFAULT, "Clp_newModel") != nullptr);
  CHECK(dlsym(RTLD_DEFAULT, "linkbox_no_such_symbol") == nullptr);
}
