#include "input/peer_case.hpp"

#include <cctype>

#include "input/cuik_file.hpp"
#include "input/minibex_file.hpp"

namespace linkbox::input {

PeerReader peer_reader_for(std::string_view file) {
  const size_t slash = file.find_last_of('/');
  const size_t dot = file.find_last_of('.');
  if (dot == std::string_view::npos || (slash != std::string_view::npos && dot < slash)) return nullptr;
  std::string extension;
  for (char c : file.substr(dot)) extension += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".bch") return read_minibex;
  if (extension == ".cuik") return read_cuik;
  return nullptr;
}

std::string peer_case_name(std::string_view file) {
  const size_t slash = file.find_last_of('/');
  std::string_view base = slash == std::string_view::npos ? file : file.substr(slash + 1);
  const size_t dot = base.find_last_of('.');
  if (dot != std::string_view::npos && dot > 0) base = base.substr(0, dot);
  return std::string(base);
}

}  // namespace linkbox::input
