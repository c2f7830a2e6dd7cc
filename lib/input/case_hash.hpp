#pragma once
// The SHA-256 of a case file's bytes, which binds a result to the case it was solved from
// (`case_sha256` in the result JSON; `linkbox check` compares it).
#include <string>

namespace linkbox::input {

// Lower-case hex digest of the file's contents; empty when the file cannot be read.
std::string case_sha256(const std::string& path);

}  // namespace linkbox::input
