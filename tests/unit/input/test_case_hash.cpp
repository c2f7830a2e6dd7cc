#include "input/case_hash.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

using linkbox::input::case_sha256;

namespace {

std::string file_with(const std::string& name, const std::string& bytes) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}

}  // namespace

TEST_CASE("a case file's SHA-256 is the standard digest of its bytes (FIPS 180-2 vectors)", "[input]") {
  CHECK(case_sha256(file_with("linkbox-hash-empty", "")) ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(case_sha256(file_with("linkbox-hash-abc", "abc")) ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // Two blocks, and a byte that is not text: the digest reads bytes, not characters.
  CHECK(case_sha256(file_with("linkbox-hash-long", "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")) ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(case_sha256(file_with("linkbox-hash-nul", std::string("a\0b", 3))) !=
        case_sha256(file_with("linkbox-hash-ab", "ab")));
}

TEST_CASE("an unreadable case file has no digest", "[input]") {
  CHECK(case_sha256("/nonexistent/linkbox/case.toml").empty());
}
