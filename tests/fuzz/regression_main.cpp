// The fuzz targets under the normal build: replays every file of the corpus folders (or files)
// given on the command line through LLVMFuzzerTestOneInput, as libFuzzer's regression mode does,
// then `--mutations N` inputs made by flipping, inserting and deleting bytes of the corpus files
// with a fixed seed (so a ctest run is the same every time). A crash or an abort fails the test.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void run(const std::string& input) {
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
}

// A small random edit of `s`: a few bytes replaced (often by digits, signs and brackets, which
// move parsers' numbers and nesting), inserted or removed.
std::string mutate(std::string s, std::mt19937& rng) {
  static const std::string interesting = "0123456789-+.eE[]{}<>\"/ \n\xff";
  const int edits = 1 + int(rng() % 4);
  for (int i = 0; i < edits; ++i) {
    const std::size_t at = s.empty() ? 0 : rng() % s.size();
    const char c = rng() % 2 ? interesting[rng() % interesting.size()] : char(rng());
    switch (rng() % 3) {
      case 0:
        if (!s.empty()) s[at] = c;
        break;
      case 1:
        s.insert(s.begin() + long(at), c);
        break;
      default:
        if (!s.empty()) s.erase(at, 1 + rng() % std::min<std::size_t>(8, s.size() - at));
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  long mutations = 0;
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--mutations" && i + 1 < argc) {
      mutations = std::strtol(argv[++i], nullptr, 10);
    } else if (fs::is_directory(arg)) {
      for (const auto& e : fs::directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
    } else {
      files.push_back(arg);
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<std::string> corpus;
  for (const fs::path& f : files) {
    corpus.push_back(read(f));
    run(corpus.back());
  }
  std::mt19937 rng(20240611);
  for (long i = 0; i < mutations && !corpus.empty(); ++i)
    run(mutate(corpus[rng() % corpus.size()], rng));
  std::printf("%zu corpus inputs and %ld mutations ran cleanly\n", corpus.size(),
              corpus.empty() ? 0L : mutations);
  return 0;
}
