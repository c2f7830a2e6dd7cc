#pragma once
// The search settings of a run: from the flags, then the case's [solve] table, then the
// defaults; or, resuming, from the checkpoint.
#include "cli/solve_command.hpp"
#include "input/case_file.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace linkbox::cli {

// cmd.options.strategy.prune holds the --prune flag (or its default) already.
void resolve_settings(SolveCommand& cmd, const input::SolveSettings& s, const std::string& file);
// A resumed run takes the checkpoint's settings; a flag that says otherwise is refused.
void resume_settings(SolveCommand& cmd, const nlohmann::json& saved);
// The settings that decide the boxes, as a checkpoint records them.
nlohmann::json search_settings(const solve::RunOptions& o);

}  // namespace linkbox::cli
