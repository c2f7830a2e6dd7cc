#include "distributed/wire.hpp"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <thread>

namespace linkbox::distributed {

namespace {

constexpr int kTag = 7;

void check(int code, const char* what, const World& world) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  world.fail(std::string("MPI error in ") + what + ": " + std::string(text, length));
}

}  // namespace

bool World::launched() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

World::World(int* argc, char*** argv) {
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    std::fprintf(stderr, "linkbox: MPI could not start\n");
    std::exit(kFaultExit);
  }
  // Errors come back to the caller, which ends the job with a message rather than letting MPI
  // abort it without one.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (provided < MPI_THREAD_FUNNELED) fail("this MPI library does not allow threads (MPI_THREAD_FUNNELED)");
}

World::~World() { MPI_Finalize(); }

void World::fail(const std::string& why) const {
  std::fprintf(stderr, "linkbox: rank %d: %s: the distributed run stops\n", rank_, why.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, kFaultExit);
  std::_Exit(kFaultExit);  // MPI_Abort does not return; this is for a library where it does
}

struct Wire::Sending {
  std::string bytes;
  MPI_Request request;
};

Wire::Wire(const World& world) : world_(world), heard_(world.size(), std::chrono::steady_clock::now()) {}

Wire::~Wire() = default;

void Wire::send(int to, Message m) {
  m.from = world_.rank();
  if (to == world_.rank()) {
    local_.push_back(std::move(m));
    return;
  }
  auto s = std::make_unique<Sending>(Sending{m.head.dump() + '\n' + m.payload, MPI_REQUEST_NULL});
  ++traffic_.messages;
  traffic_.bytes += static_cast<long>(s->bytes.size());
  if (m.head.value("t", "") == "beat") {
    ++traffic_.beats;
    traffic_.beat_bytes += static_cast<long>(s->bytes.size());
  }
  check(MPI_Isend(s->bytes.data(), static_cast<int>(s->bytes.size()), MPI_CHAR, to, kTag, MPI_COMM_WORLD, &s->request),
        "MPI_Isend", world_);
  sending_.push_back(std::move(s));
  progress();
}

void Wire::progress() {
  for (size_t k = 0; k < sending_.size();) {
    int done = 0;
    check(MPI_Test(&sending_[k]->request, &done, MPI_STATUS_IGNORE), "MPI_Test", world_);
    if (done) {
      sending_[k] = std::move(sending_.back());
      sending_.pop_back();
    } else {
      ++k;
    }
  }
}

std::optional<Message> Wire::receive() {
  progress();
  if (!local_.empty()) {
    Message m = std::move(local_.front());
    local_.pop_front();
    return m;
  }
  int flag = 0;
  MPI_Status status;
  check(MPI_Iprobe(MPI_ANY_SOURCE, kTag, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe", world_);
  if (!flag) return std::nullopt;
  int count = 0;
  check(MPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count", world_);
  std::string bytes(static_cast<size_t>(count), '\0');
  check(MPI_Recv(bytes.data(), count, MPI_CHAR, status.MPI_SOURCE, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv",
        world_);
  heard_[status.MPI_SOURCE] = std::chrono::steady_clock::now();
  Message m;
  m.from = status.MPI_SOURCE;
  const size_t cut = bytes.find('\n');
  try {
    m.head = nlohmann::json::parse(bytes.substr(0, cut));
  } catch (const nlohmann::json::exception& e) {
    world_.fail("a damaged message from rank " + std::to_string(m.from) + ": " + e.what());
  }
  if (cut != std::string::npos) m.payload = bytes.substr(cut + 1);
  return m;
}

void Wire::flush(double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (progress(), !sending_.empty()) {
    if (std::chrono::steady_clock::now() > until) world_.fail("messages still unsent after " + std::to_string(seconds) + " s");
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

double Wire::silent(int rank) const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - heard_[rank]).count();
}

}  // namespace linkbox::distributed
