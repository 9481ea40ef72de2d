/*!
  \file vpFuzzReplay.cpp
  \brief Replay driver: runs a fuzz target's LLVMFuzzerTestOneInput on every file of the given directories.

  Why: the fuzz targets are built with libFuzzer only by clang (./vispmorph fuzz); linked with this main
  instead, the same sources run under the normal gcc build and in ctest, so the seed corpus and every input
  that once crashed (tests/fuzz/regressions/) are replayed on each test run and the fixes stay fixed.
  Usage: fuzz_<target>_replay DIR|FILE... ; files whose name starts with '.' are skipped (.gitkeep).
  A crash or a violated invariant aborts (the test fails); a missing directory or no input at all is an error.
*/
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv)
{
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (int a = 1; a < argc; ++a) {
    const fs::path p(argv[a]);
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) {
      files.push_back(p);
    } else if (fs::is_directory(p, ec)) {
      for (const fs::directory_entry &e : fs::directory_iterator(p))
        if (e.is_regular_file() && e.path().filename().string().rfind('.', 0) != 0)
          files.push_back(e.path());
    } else {
      std::fprintf(stderr, "replay: no such file or directory: %s\n", argv[a]);
      return 2;
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "replay: no input to replay\n");
    return 2;
  }
  std::sort(files.begin(), files.end()); // a deterministic order
  for (const fs::path &f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::fprintf(stderr, "replay: %s (%zu bytes)\n", f.string().c_str(), bytes.size());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t *>(bytes.data()), bytes.size());
  }
  std::printf("replayed %zu inputs\n", files.size());
  return 0;
}
