#pragma once
// A case file, read (input/) and turned into its formulation: the "load" step of the pipeline.
#include "formulate/formulation.hpp"
#include "input/case_file.hpp"

#include <memory>
#include <string>
#include <string_view>

namespace linkbox::formulate {

struct LoadedCase {
  std::string kind, name, file;
  std::unique_ptr<Formulation> formulation;
  input::SolveSettings solve;  // the case's recommended settings
};

// Throws input::InputError for anything wrong with the case, including a linkage that cannot
// be assembled; an unexpected failure while loading is reported the same way (line 0).
std::unique_ptr<Formulation> formulate(const input::Case& c);
LoadedCase load_case(const std::string& path);
LoadedCase load_case_text(std::string_view text, const std::string& file);

}  // namespace linkbox::formulate
