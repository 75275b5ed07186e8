// Output files appear whole or not at all: a writer fills a temporary sibling of the target, which
// is renamed into place only when the writer returns. A crash, a kill or an exception leaves no
// half-written file under the final name.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace wisp::io {

// Checks that `path` can be written (its folder exists and is writable, and it is not itself a
// folder), so that commands refuse a bad output path before any work. Throws
// std::runtime_error naming `path`.
void check_writable(const std::filesystem::path& path);

// Calls write(tmp) with a temporary path in the same folder as `path` (same extension, so writers
// that pick a format from the extension still work), then renames tmp to path. If write throws,
// the temporary is removed and the exception propagates. Throws std::runtime_error naming `path`
// when the folder is not writable or the rename fails.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

// Writes `text` to `path` atomically (the same rules).
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace wisp::io
