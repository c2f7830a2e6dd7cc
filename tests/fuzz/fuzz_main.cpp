// libFuzzer entry point of one target (LINKBOX_FUZZ_TARGET, a name from targets.cpp).
#include "targets.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#ifndef LINKBOX_FUZZ_TARGET
#error "LINKBOX_FUZZ_TARGET must name the target"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const linkbox::fuzz::Target* target = [] {
    const auto* t = linkbox::fuzz::find_target(LINKBOX_FUZZ_TARGET);
    if (!t) {
      std::fprintf(stderr, "no fuzz target named %s\n", LINKBOX_FUZZ_TARGET);
      std::abort();
    }
    return t;
  }();
  target->run(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
