#include "report/version.hpp"

namespace linkbox::report {

const char* linkbox_version() { return LINKBOX_VERSION; }

}  // namespace linkbox::report
