#include "cli/interrupts.hpp"

#include <csignal>
#include <unistd.h>

namespace linkbox::cli {

namespace {

std::atomic<int> count{0};
volatile std::sig_atomic_t last_signal = 0;

void on_signal(int sig) {
  last_signal = sig;
  static const char first[] =
      "\nlinkbox: interrupted: the search stops at the next box; what was found is verified and written "
      "(interrupt again to skip verification)\n";
  static const char second[] = "\nlinkbox: interrupted again: verification skipped\n";
  const bool again = count.fetch_add(1) > 0;
  // write(2) is async-signal-safe; stdio is not.
  [[maybe_unused]] auto n = again ? write(2, second, sizeof second - 1) : write(2, first, sizeof first - 1);
}

}  // namespace

void catch_interrupts() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

const std::atomic<int>& interrupts() { return count; }

int interrupt_exit_code() { return count.load() ? 128 + last_signal : 0; }

}  // namespace linkbox::cli
