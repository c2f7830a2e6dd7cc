#pragma once
// Jobs 0..n-1 on a few threads, each job once, taken in increasing order as threads free up.
#include <cstddef>
#include <functional>

namespace linkbox::solve {

// Runs job(i) for every i < n on `threads` threads (this one among them). The first exception
// stops the handing out of jobs; it is rethrown once every thread is back.
void run_jobs(size_t n, int threads, const std::function<void(size_t)>& job);

}  // namespace linkbox::solve
