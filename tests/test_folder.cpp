// Test folders removed at the end of the process (see test_folder.hpp).
#include "tests/test_folder.hpp"

#include <unistd.h>

#include <cstdlib>
#include <mutex>
#include <set>
#include <system_error>

namespace wisp::test {
namespace {

// The folders made so far; its destructor, at the process's normal end, removes them.
struct MadeFolders {
  std::mutex mutex;
  std::set<std::filesystem::path> paths;

  ~MadeFolders() {
    if (std::getenv("WISP_KEEP_TEST_FILES")) return;
    std::error_code ignored;  // a folder a test removed itself is fine
    for (const std::filesystem::path& p : paths) std::filesystem::remove_all(p, ignored);
  }
};

MadeFolders& made() {
  static MadeFolders folders;
  return folders;
}

}  // namespace

std::filesystem::path test_folder(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("wisp_test_" + name + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  MadeFolders& m = made();
  const std::lock_guard<std::mutex> lock(m.mutex);
  m.paths.insert(dir);
  return dir;
}

std::string fresh_folder(const std::string& name) {
  const std::filesystem::path dir = test_folder(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace wisp::test
