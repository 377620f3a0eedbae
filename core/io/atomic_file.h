#pragma once
// Write-to-temporary-then-rename, so a crash or a full disk never leaves a half-written file and
// never destroys the previous version.
#include <functional>
#include <string>

namespace pmsim {

// Calls write(tmp_path) with a unique temporary path in the folder of `path`, then renames it onto
// `path`. On any failure the temporary file is removed, `path` is untouched, and
// std::runtime_error names `path` and the reason.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);
// Convenience for text.
void write_text_atomically(const std::string& path, const std::string& text);

}  // namespace pmsim
