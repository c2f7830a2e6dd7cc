#include "prune/lp/lp_record.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace linkbox::prune::lp {

namespace {

// Threads (one solver each) append whole blocks under one lock, so blocks never interleave.
std::mutex& file_mutex() {
  static std::mutex m;
  return m;
}

void put(std::string& out, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, " %a", v);  // exact; "inf" and "-inf" read back by strtod
  out += buf;
}

char status_char(LpStatus s) { return s == LpStatus::bounded ? 'b' : s == LpStatus::infeasible ? 'i' : 'u'; }

class Recorder final : public LpSolver {
 public:
  Recorder(std::unique_ptr<LpSolver> inner, std::string path, long every)
      : inner_(std::move(inner)), path_(std::move(path)), every_(every < 1 ? 1 : every) {}
  ~Recorder() override { flush(); }

  std::string name() const override { return inner_->name(); }
  void load(const LinearProgram& p) override {
    flush();
    inner_->load(p);
    recording_ = loads_++ % every_ == 0;
    if (!recording_) return;
    block_ = "lp " + inner_->name() + " " + std::to_string(p.num_cols()) + " " + std::to_string(p.num_rows()) + "\n";
    for (int j = 0; j < p.num_cols(); ++j) {
      block_ += "c";
      put(block_, p.col_lo[j]);
      put(block_, p.col_hi[j]);
      block_ += "\n";
    }
    for (int i = 0; i < p.num_rows(); ++i) {
      block_ += "r";
      put(block_, p.row_lo[i]);
      put(block_, p.row_hi[i]);
      auto idx = p.row_indices(i);
      auto val = p.row_values(i);
      block_ += " " + std::to_string(idx.size());
      for (size_t k = 0; k < idx.size(); ++k) {
        block_ += " " + std::to_string(idx[k]);
        put(block_, val[k]);
      }
      block_ += "\n";
    }
  }
  void set_column_bounds(int col, double lo, double hi) override {
    inner_->set_column_bounds(col, lo, hi);
    if (!recording_) return;
    block_ += "b " + std::to_string(col);
    put(block_, lo);
    put(block_, hi);
    block_ += "\n";
  }
  LpBound minimize(int col) override { return note(col, 1, inner_->minimize(col)); }
  LpBound maximize(int col) override { return note(col, -1, inner_->maximize(col)); }
  bool last_point(std::vector<double>& x) const override { return inner_->last_point(x); }
  long iterations() const override { return inner_->iterations(); }
  double operations() const override { return inner_->operations(); }
  LpPaths paths() const override { return inner_->paths(); }

 private:
  LpBound note(int col, int sense, LpBound b) {
    if (recording_) {
      block_ += "s " + std::to_string(col) + " " + std::to_string(sense) + " " + status_char(b.status);
      put(block_, b.value);
      block_ += "\n";
    }
    return b;
  }
  void flush() {
    if (block_.empty()) return;
    block_ += "end\n";
    std::lock_guard<std::mutex> lock(file_mutex());
    if (std::FILE* f = std::fopen(path_.c_str(), "a")) {
      std::fwrite(block_.data(), 1, block_.size(), f);
      std::fclose(f);
    }
    block_.clear();
  }

  std::unique_ptr<LpSolver> inner_;
  std::string path_;
  long every_;
  long loads_ = 0;
  bool recording_ = false;
  std::string block_;
};

double get_double(std::istringstream& in) {
  std::string token;
  if (!(in >> token)) throw std::runtime_error("LP record: missing number");
  char* end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0') throw std::runtime_error("LP record: bad number '" + token + "'");
  return v;
}

}  // namespace

std::unique_ptr<LpSolver> record_if_asked(std::unique_ptr<LpSolver> inner) {
  const char* path = std::getenv("LINKBOX_LP_RECORD");
  if (!path || !*path) return inner;
  const char* every = std::getenv("LINKBOX_LP_RECORD_EVERY");
  return std::make_unique<Recorder>(std::move(inner), path, every ? std::atol(every) : 1);
}

std::vector<RecordedLp> read_lp_record(const std::string& path, size_t limit) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("LP record: cannot open " + path);
  std::vector<RecordedLp> out;
  std::string line;
  RecordedLp* current = nullptr;
  std::vector<double> lo, hi;  // the column bounds as the solves saw them
  while (std::getline(file, line)) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "lp") {
      if (limit && out.size() == limit) break;
      current = &out.emplace_back();
      int n = 0, m = 0;
      in >> current->backend >> n >> m;
      for (int j = 0; j < n; ++j) {
        if (!std::getline(file, line)) throw std::runtime_error("LP record: truncated columns");
        std::istringstream c(line);
        c >> tag;
        const double l = get_double(c), h = get_double(c);
        current->program.add_column(l, h);
      }
      std::vector<std::pair<int, double>> row;
      for (int i = 0; i < m; ++i) {
        if (!std::getline(file, line)) throw std::runtime_error("LP record: truncated rows");
        std::istringstream r(line);
        r >> tag;
        const double l = get_double(r), h = get_double(r);
        size_t k = 0;
        r >> k;
        row.clear();
        for (size_t t = 0; t < k; ++t) {
          int j = -1;
          r >> j;
          row.push_back({j, get_double(r)});
        }
        current->program.add_row(row, l, h);
      }
      lo = current->program.col_lo;
      hi = current->program.col_hi;
    } else if (tag == "b" && current) {
      int col = -1;
      in >> col;
      if (col < 0 || col >= static_cast<int>(lo.size())) throw std::runtime_error("LP record: bad column");
      lo[col] = get_double(in);
      hi[col] = get_double(in);
    } else if (tag == "s" && current) {
      RecordedSolve s;
      int sense = 0;
      char status = 0;
      in >> s.col >> sense >> status;
      s.sense = sense;
      s.answer.status = status == 'b' ? LpStatus::bounded : status == 'i' ? LpStatus::infeasible : LpStatus::unknown;
      s.answer.value = get_double(in);
      s.col_lo = lo;
      s.col_hi = hi;
      current->solves.push_back(std::move(s));
    } else if (tag == "end") {
      current = nullptr;
    } else if (!tag.empty()) {
      throw std::runtime_error("LP record: unexpected line '" + line.substr(0, 40) + "'");
    }
  }
  return out;
}

}  // namespace linkbox::prune::lp
