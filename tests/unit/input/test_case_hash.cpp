#include "input/case_hash.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

using linkbox::input::case_sha256;

namespace {

// The digest of a file holding `bytes`, written and removed here.
std::string digest_of(const std::string& bytes) {
  // One name per process: test runs side by side (ctest -j, two builds) do not share the file.
  const auto path = std::filesystem::temp_directory_path() / ("linkbox-test-case-hash-" + std::to_string(::getpid()));
  std::ofstream(path, std::ios::binary) << bytes;
  const std::string digest = case_sha256(path.string());
  std::filesystem::remove(path);
  return digest;
}

}  // namespace

TEST_CASE("a case file's SHA-256 is the standard digest of its bytes (FIPS 180-2 vectors)", "[input]") {
  CHECK(digest_of("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(digest_of("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // 448 bits: the padding needs a second block.
  CHECK(digest_of("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  // A NUL byte is hashed like any other (Python's hashlib.sha256(b"a\0b")).
  CHECK(digest_of(std::string("a\0b", 3)) == "59b271ae1bbcb1d31d41929817f4b16fb439eb4f31520b5ad1d5ce98920a7138");
}

TEST_CASE("an unreadable case file has no digest", "[input]") {
  CHECK(case_sha256("/nonexistent/linkbox/case.toml").empty());
}
