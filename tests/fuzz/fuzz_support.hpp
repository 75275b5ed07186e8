// What every fuzz target shares: the input written to a file (the readers under test take paths,
// as the commands do), the check that a refusal is one clean line, and the stage that consumes a
// parsed input: one tiny frame rendered end to end (simulate, project, wisps, arrangement, solve).
// Each target is a libFuzzer entry point, LLVMFuzzerTestOneInput, built two ways
// (tests/fuzz/CMakeLists.txt): with clang and -DWISP_FUZZ=ON as a real fuzzer under ASan and
// UBSan, and under the normal build with regression_main.cpp, which replays the target's corpus.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "io/scene.hpp"

namespace wisp::fuzz {

// This process's scratch folder (created once, under $TMPDIR or /tmp).
const std::filesystem::path& scratch();

// Writes bytes to scratch() / name and returns the path.
std::filesystem::path write_input(const std::string& name, const std::uint8_t* data,
                                  std::size_t size);
std::filesystem::path write_input(const std::string& name, const std::string& text);

// Runs `body` on `input` (the fuzzer's bytes); a std::exception is a refusal, which must be one
// non-empty line with no library internals in it (else the process aborts, which the fuzzer
// reports as a crash). A word the input itself contains is the input echoed, not an internal:
// libFuzzer learns the words from the comparisons here and writes them into its inputs.
void expect_clean(const std::uint8_t* input, std::size_t size, const std::function<void()>& body);

// The scene of a tiny frame: 24x24 pixels, a few short guides, one frame simulated cheaply.
// Fields the input gave are kept where they do not make the run bigger.
io::Scene tiny(io::Scene scene);

// Simulates (or reads `anim`), projects and renders the first frame of tiny(scene).
void render_tiny(const io::Scene& scene, const std::filesystem::path& anim = {});

}  // namespace wisp::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
