#pragma once
// The fuzz targets of tests/fuzz: each takes one input and feeds it to a reader the way the
// CLI would. Expected rejections (InputError and other std::invalid_argument, the expression
// parser's ParseError, nlohmann's json exceptions, which the CLI turns into exit code 2) are
// swallowed; anything else escapes: another exception, an abort, a sanitizer report, or a
// hang. The same functions run under libFuzzer (fuzz_main.cpp, clang) and, over the saved
// corpus and regressions, in the ordinary Release test suite (test_fuzz_inputs.cpp).
#include <string>
#include <string_view>
#include <vector>

namespace linkbox::fuzz {

struct Target {
  const char* name;  // also the folder under corpus/ and regressions/
  void (*run)(std::string_view input);
};

// Every target, in a fixed order.
const std::vector<Target>& targets();

// The target called `name`, or nullptr.
const Target* find_target(std::string_view name);

}  // namespace linkbox::fuzz
