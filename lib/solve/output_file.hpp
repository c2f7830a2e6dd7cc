#pragma once
// Writing a result, checkpoint or tree file where the user pointed. "-" is standard output;
// anything that is not a regular file (a terminal, /dev/null, a FIFO) is written in place; a
// symbolic link is followed, never replaced; a regular file is replaced atomically (a
// temporary file beside the link's target, flushed, then a rename), so a crash mid-write
// leaves the previous file whole.
#include <string>

namespace linkbox::solve {

// Throws std::runtime_error when nothing could be written. When neither the atomic route nor
// writing in place works, the text is kept in a file of the temporary folder, and the error
// names it: a finished run never loses its result.
void write_output(const std::string& path, const std::string& text);

// Why `path` cannot be written as write_output writes it, or "" when it can: for a regular
// file, the temporary file is created (and removed) where the rename needs it, or the file
// itself opened for appending (the in-place fallback). Checked before the work starts.
std::string output_problem(const std::string& path);

}  // namespace linkbox::solve
