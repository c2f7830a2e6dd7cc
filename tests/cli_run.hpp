#pragma once
// What tests that drive the `linkbox` executable share: source paths, a scratch folder per
// test process, running the CLI (exit code and output), reading a result JSON.
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace linkbox::test {

inline std::string src(const std::string& p) { return std::string(LINKBOX_SOURCE_DIR) + "/" + p; }

// A file in a fresh folder of this process's, not the working directory.
inline std::string scratch(const std::string& name) {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("linkbox-tests-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return (dir / name).string();
}

struct Ran {
  int code;
  std::string out;  // stdout and stderr
};

inline Ran run_cli(const std::string& args) {
  const std::string log = scratch("cli-output.txt");
  const std::string cmd = std::string(LINKBOX_CLI) + " " + args + " > " + log + " 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

inline nlohmann::json read_json(const std::string& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

}  // namespace linkbox::test
