#pragma once
// What the parser does not say itself: `linkbox help [SUBCOMMAND]`, and an unknown subcommand
// or flag named with the nearest known one.
namespace CLI {
class App;
}

namespace linkbox::cli {

// Looks at the arguments before CLI11 parses them. Answers `help` and usage errors (printed
// when `speaks`): returns the exit code then, or -1 when the parse should go on.
int answer_before_parse(const CLI::App& app, int argc, char** argv, bool speaks);

}  // namespace linkbox::cli
