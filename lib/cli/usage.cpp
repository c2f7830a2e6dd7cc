#include "cli/usage.hpp"

#include "cli/ending.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace linkbox::cli {

namespace {

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// "; did you mean X?" for the nearest of `known` when it is near enough to be a slip, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& known) {
  const std::string* best = nullptr;
  size_t distance = 0;
  for (auto& k : known)
    if (const size_t d = edit_distance(word, k); !best || d < distance) best = &k, distance = d;
  const bool prefix = best && word.size() >= 2 && best->rfind(word, 0) == 0;
  return best && (prefix || distance <= std::max<size_t>(2, word.size() / 3)) ? "; did you mean " + *best + "?" : "";
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names{"help"};
  for (auto* s : app.get_subcommands({})) names.push_back(s->get_name());
  return names;
}

std::vector<std::string> flag_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (auto* o : app.get_options()) {
    for (auto& l : o->get_lnames()) names.push_back("--" + l);
    for (auto& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

int usage_error(const std::string& what, bool speaks) {
  if (speaks) std::fprintf(stderr, "%s\nRun `linkbox --help` for the subcommands.\n", what.c_str());
  return exit_bad_input;
}

bool is_number(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0';
}

// The first argument of `sub` that names no flag of it, or "".
std::string unknown_flag(const CLI::App& sub, int argc, char** argv) {
  for (int i = 2; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--") break;
    if (a.size() < 2 || a[0] != '-' || is_number(a)) continue;
    if (a.rfind("--", 0) == 0) a = a.substr(0, a.find('='));
    else a = a.substr(0, 2);  // -x or -xVALUE
    if (!sub.get_option_no_throw(a)) return a;
  }
  return "";
}

int help(const CLI::App& app, int argc, char** argv, bool speaks) {
  if (argc < 3) {
    if (speaks) std::printf("%s\n", app.help().c_str());
    return exit_exact;
  }
  const std::string name = argv[2];
  for (auto* s : app.get_subcommands({}))
    if (s->get_name() == name) {
      if (speaks) std::printf("%s\n", s->help("linkbox").c_str());
      return exit_exact;
    }
  return usage_error("linkbox help: no subcommand '" + name + "'" + did_you_mean(name, subcommand_names(app)), speaks);
}

}  // namespace

int answer_before_parse(const CLI::App& app, int argc, char** argv, bool speaks) {
  if (argc < 2) return usage_error("linkbox: a subcommand is required: solve, resume, check or convert", speaks);
  const std::string first = argv[1];
  if (first == "help") return help(app, argc, argv, speaks);
  if (first[0] == '-') {
    if (app.get_option_no_throw(first.substr(0, first.find('=')))) return -1;
    return usage_error("linkbox: unknown flag " + first + did_you_mean(first, flag_names(app)) +
                           " (the flags of a run come after its subcommand: linkbox solve CASE " + first + ")",
                       speaks);
  }
  const CLI::App* sub = nullptr;
  for (auto* s : app.get_subcommands({}))
    if (s->get_name() == first) sub = s;
  if (!sub) return usage_error("linkbox: unknown subcommand '" + first + "'" + did_you_mean(first, subcommand_names(app)), speaks);
  if (const std::string flag = unknown_flag(*sub, argc, argv); !flag.empty())
    return usage_error("linkbox " + first + ": unknown flag " + flag + did_you_mean(flag, flag_names(*sub)), speaks);
  return -1;
}

}  // namespace linkbox::cli
