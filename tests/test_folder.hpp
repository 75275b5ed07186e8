// Folders for a test's files under the system's temporary folder. Each is removed when the test
// process ends, so that running the suite leaves nothing behind (ctest runs every test case in a
// process of its own); set WISP_KEEP_TEST_FILES to keep them, e.g. to look at a failure's output.
// Names carry the process id, so parallel test processes and two build trees never share one.
#pragma once

#include <filesystem>
#include <string>

namespace wisp::test {

// The folder `name` of this process, made if it is missing (a test may have removed it), with
// whatever earlier calls left in it.
std::filesystem::path test_folder(const std::string& name);

// The same folder, emptied.
std::string fresh_folder(const std::string& name);

}  // namespace wisp::test
