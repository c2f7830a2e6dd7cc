#pragma once
// SIGINT and SIGTERM: the first stops the search at the next box (what was found is still
// verified and written), the second skips verification.
#include <atomic>

namespace linkbox::cli {

void catch_interrupts();
const std::atomic<int>& interrupts();  // how many arrived
// The exit code of a run that went on to its end: 128 + the last signal once one arrived, else 0.
int interrupt_exit_code();

}  // namespace linkbox::cli
