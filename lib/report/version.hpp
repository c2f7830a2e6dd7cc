#pragma once
// What a result JSON says about the program that wrote it. `kResultFormat` changes whenever
// a key changes meaning or goes away (docs/result.schema.json describes that format).

namespace linkbox::report {

inline constexpr int kResultFormat = 1;
const char* linkbox_version();  // the project version, e.g. "0.3.0"

}  // namespace linkbox::report
