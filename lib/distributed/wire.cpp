#include "distributed/wire.hpp"

#include <mpi.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <unistd.h>

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

Traffic& Traffic::operator+=(const Traffic& o) {
  messages += o.messages, bytes += o.bytes, beats += o.beats, beat_bytes += o.beat_bytes;
  return *this;
}

void Traffic::put(nlohmann::json& head) const {
  head["messages"] = messages, head["bytes"] = bytes, head["beats"] = beats, head["beat_bytes"] = beat_bytes;
}

Traffic Traffic::from(const nlohmann::json& head) {
  return {head.at("messages").get<long>(), head.at("bytes").get<long>(), head.at("beats").get<long>(),
          head.at("beat_bytes").get<long>()};
}

double fault_timeout() {
  const char* t = std::getenv("LINKBOX_MPI_TIMEOUT");
  const double s = t ? std::atof(t) : 0;
  return s > 0 ? s : 60;
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

void World::fail(const std::string& why, int code) const {
  std::fprintf(stderr, "linkbox: rank %d: %s: the distributed run stops\n", rank_, why.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return; this is for a library where it does
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
  if (const std::string t = m.head.value("t", ""); t == "beat" || t == "v-beat") {
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

void Outbox::post(int to, Message m) {
  std::lock_guard lock(m_);
  queue_.emplace_back(to, std::move(m));
  cv_.notify_one();
}

bool Outbox::drain(Wire& wire) {
  std::deque<std::pair<int, Message>> out;
  {
    std::lock_guard lock(m_);
    out.swap(queue_);
  }
  for (auto& [to, m] : out) wire.send(to, std::move(m));
  return !out.empty();
}

void Outbox::pause() {
  std::unique_lock lock(m_);
  cv_.wait_for(lock, std::chrono::microseconds(500), [&] { return !queue_.empty(); });
}

TestDeath::TestDeath(int rank, const std::string& phase) {
  const char* r = std::getenv("LINKBOX_MPI_TEST_DIE_RANK");
  if (!r || std::atoi(r) != rank) return;
  const char* in = std::getenv("LINKBOX_MPI_TEST_DIE_IN");
  if (phase != (in ? in : "search")) return;
  const char* a = std::getenv("LINKBOX_MPI_TEST_DIE_AFTER");
  after_ = a ? std::atol(a) : 20;
  const char* how = std::getenv("LINKBOX_MPI_TEST_DIE_HOW");
  hang_ = how && std::string(how) == "hang";
}

void TestDeath::step() {
  if (after_ < 0 || steps_.fetch_add(1) < after_) return;
  if (hang_) raise(SIGSTOP);  // every thread of the process stops: no heartbeat either
  _exit(kFaultExit);
}

}  // namespace linkbox::distributed
