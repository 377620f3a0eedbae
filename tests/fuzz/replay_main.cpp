// Replays fuzz inputs through the same entry functions the fuzzers use, in the ordinary build
// (gcc, no libFuzzer): every crash a fuzzer ever found is kept in tests/fuzz/regressions/<target>/
// and runs as a ctest test, and the seed corpora built from assets/ are replayed too.
//
//   pmsim_fuzz_replay TARGET PATH...      each PATH a file or a folder (all files below it)
//   pmsim_fuzz_replay --seeds TARGET OUT  write TARGET's seed corpus (from assets/) into OUT
//   pmsim_fuzz_replay --list              the target names
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/base/asset_locator.h"
#include "tests/fuzz/fuzz_targets.h"

namespace {

struct Target {
  const char* name;
  int (*entry)(const std::uint8_t*, std::size_t);
  void (*seeds)(const std::string&, const std::string&);
};

const Target kTargets[] = {
#define PMSIM_FUZZ_ROW(n) {#n, &pmsim::fuzz::n, &pmsim::fuzz::n##_seeds},
    PMSIM_FUZZ_TARGETS(PMSIM_FUZZ_ROW)
#undef PMSIM_FUZZ_ROW
};

const Target* find(const std::string& name) {
  for (const Target& t : kTargets)
    if (name == t.name) return &t;
  std::fprintf(stderr, "pmsim_fuzz_replay: unknown target '%s'\n", name.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--list") == 0) {
    for (const Target& t : kTargets) std::printf("%s\n", t.name);
    return 0;
  }
  if (argc == 4 && std::strcmp(argv[1], "--seeds") == 0) {
    std::filesystem::create_directories(argv[3]);
    find(argv[2])->seeds(pmsim::asset_dir(), argv[3]);
    return 0;
  }
  if (argc < 3) {
    std::fprintf(stderr, "usage: pmsim_fuzz_replay TARGET PATH... | --seeds TARGET OUT | --list\n");
    return 2;
  }
  const Target* t = find(argv[1]);
  std::vector<std::filesystem::path> files;
  for (int i = 2; i < argc; ++i) {
    const std::filesystem::path p(argv[i]);
    if (std::filesystem::is_directory(p)) {
      for (const auto& e : std::filesystem::recursive_directory_iterator(p))
        if (e.is_regular_file() && e.path().filename().string()[0] != '.' &&
            e.path().filename() != "README.md")
          files.push_back(e.path());
    } else if (std::filesystem::is_regular_file(p)) {
      files.push_back(p);
    } else {
      std::fprintf(stderr, "pmsim_fuzz_replay: no such file or folder: %s\n", argv[i]);
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  std::size_t skipped = 0;
  for (const auto& f : files) {
    // A known, not yet fixed bug (like a gtest DISABLED_ test): named after its finding.
    if (f.filename().string().rfind("DISABLED_", 0) == 0) {
      std::fprintf(stderr, "%s: %s skipped (open finding)\n", t->name, f.string().c_str());
      ++skipped;
      continue;
    }
    std::ifstream in(f, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::fprintf(stderr, "%s: %s (%zu bytes)\n", t->name, f.string().c_str(), bytes.size());
    t->entry(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());  // aborts on a violation
  }
  std::printf("%s: %zu inputs replayed, no oracle violated (%zu disabled)\n", t->name, files.size() - skipped,
              skipped);
  return 0;
}
