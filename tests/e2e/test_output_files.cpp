// Where results go (solve/output_file.hpp): "-" is standard output and alone there, a link is
// followed and stays a link, a FIFO is written in place and stays a FIFO, and what cannot be
// written is bad input found before the work.
#include "tests/cli_run.hpp"
#include "solve/output_file.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

using namespace linkbox;
using namespace linkbox::test;

namespace {

std::string read_text(const std::string& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string kCase = src("cases/spherical/wrist.toml");

}  // namespace

TEST_CASE("JSON asked on standard output (json -) comes alone, the summary on stderr", "[cli][output]") {
  const std::string out = scratch("stdout.json"), err = scratch("stderr.txt");
  const std::string cmd = std::string(LINKBOX_CLI) + " solve " + kCase + " --json - > " + out + " 2> " + err;
  REQUIRE(std::system(cmd.c_str()) == 0);
  const nlohmann::json j = read_json(out);  // throws if anything else is mixed in
  CHECK(j.at("headline").get<std::string>().rfind("exactly 2 roots", 0) == 0);
  CHECK(read_text(err).find("verification") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists("-"));
}

TEST_CASE("a link given to --json is followed and stays a link", "[cli][output]") {
  const std::string target = scratch("linked-target.json"), link = scratch("link.json");
  std::filesystem::remove(target);
  std::filesystem::remove(link);
  std::filesystem::create_symlink(target, link);  // dangling until the run writes its target
  REQUIRE(run_cli("solve " + kCase + " --quiet --json " + link).code == 0);
  CHECK(std::filesystem::is_symlink(link));
  CHECK(read_json(target).contains("headline"));
  REQUIRE(run_cli("solve " + kCase + " --quiet --json " + link).code == 0);  // an existing target
  CHECK(std::filesystem::is_symlink(link));
  CHECK_FALSE(std::filesystem::exists(target + ".tmp"));
}

TEST_CASE("a FIFO given to --json is written in place and stays a FIFO", "[cli][output]") {
  const std::string fifo = scratch("result.fifo"), got = scratch("fifo-read.json");
  std::filesystem::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const std::string reader = "timeout 60 cat " + fifo + " > " + got + " &";
  REQUIRE(std::system(reader.c_str()) == 0);
  REQUIRE(run_cli("solve " + kCase + " --quiet --json " + fifo).code == 0);
  CHECK(std::filesystem::is_fifo(fifo));
  for (int k = 0; k < 100 && read_text(got).empty(); ++k) ::usleep(50000);
  CHECK(read_text(got).find("\"headline\"") != std::string::npos);
  std::filesystem::remove(fifo);
}

TEST_CASE("outputs that cannot be written are found before the work", "[cli][output]") {
  CHECK(solve::output_problem(scratch("")) == "is a folder");
  CHECK(solve::output_problem(scratch("no-such-folder/out.json")).rfind("cannot write there", 0) == 0);
  CHECK(solve::output_problem("-").empty());
  CHECK(solve::output_problem(scratch("fresh.json")).empty());
  CHECK_FALSE(std::filesystem::exists(scratch("fresh.json")));
  CHECK_FALSE(std::filesystem::exists(scratch("fresh.json.tmp")));
  CHECK(run_cli("solve " + kCase + " --checkpoint -").code == 2);
  const Ran r = run_cli("solve " + kCase + " --json " + scratch("no-such-folder/out.json"));
  CHECK(r.code == 2);
  CHECK(r.out.find("cannot write there") != std::string::npos);
}
