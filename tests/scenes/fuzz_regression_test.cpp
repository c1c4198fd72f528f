// Replays the fuzzing seed corpora and the saved fuzzer findings (tests/fuzz/corpus/<loader>/ and
// tests/fuzz/regressions/<loader>/) through exactly the code the libFuzzer harnesses run (tests/fuzz/fuzz_targets.h),
// so every past crash stays fixed in the normal suite and under the asan preset, without clang or libFuzzer.
// Each input must load or throw kiln::Error: any other exception fails the test, a crash or sanitizer report fails
// the run. Corpus seeds named ok_* must load: they are the valid scenes the fuzzer mutates, and they reach the deep
// code only while the fixtures they reference still work.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_targets.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using fuzz::Loader;

const fs::path kFuzzDir = fs::path(KILN_SOURCE_DIR) / "tests" / "fuzz";

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.is_regular_file()) out.push_back(entry.path());
  std::sort(out.begin(), out.end());  // stable order for readable failures
  return out;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One scratch folder per input folder: ctest runs the tests as parallel processes, and XML/JSON inputs are written
// to scratch/input.xml (.json) before loading.
fs::path scratch_for(const fs::path& input_dir) {
  const fs::path dir =
      fs::path(KILN_TEST_TMP) / "fuzz_regression" / input_dir.parent_path().filename() / input_dir.filename();
  fs::create_directories(dir);
  fuzz::write_fixtures(dir);
  return dir;
}

// Feeds every file of `dir`; returns how many there were.
size_t replay(Loader l, const fs::path& dir, bool ok_prefix_must_load) {
  const fs::path scratch = scratch_for(dir);
  const auto files = files_in(dir);
  for (const auto& f : files) {
    SCOPED_TRACE(f.string());
    fuzz::Outcome outcome;
    try {
      outcome = fuzz::run_loader(l, read_all(f), scratch);
    } catch (const std::exception& e) {  // InvariantViolation or an exception that is not a kiln::Error
      ADD_FAILURE() << e.what();
      continue;
    }
    if (ok_prefix_must_load && f.filename().string().rfind("ok_", 0) == 0) {
      EXPECT_TRUE(outcome.loaded) << "an ok_ seed must load, got: " << outcome.error;
    }
  }
  return files.size();
}

class FuzzRegression : public testing::TestWithParam<Loader> {};

TEST_P(FuzzRegression, SeedCorpusLoadsOrThrowsKilnError) {
  const fs::path dir = kFuzzDir / "corpus" / std::string(fuzz::loader_name(GetParam()));
  ASSERT_TRUE(fs::is_directory(dir)) << dir << " is missing: the fuzzer has no seeds";
  EXPECT_GE(replay(GetParam(), dir, true), 3u) << "too few seeds in " << dir;
}

// Every loader has saved inputs: its past findings, or inputs the fuzzer generated and minimised (.ci/fuzz.sh says
// how), so the case replays something for every loader.
TEST_P(FuzzRegression, SavedFindingsLoadOrThrowKilnError) {
  const fs::path dir = kFuzzDir / "regressions" / std::string(fuzz::loader_name(GetParam()));
  ASSERT_TRUE(fs::is_directory(dir)) << dir << " is missing: save fuzzer-generated inputs there (.ci/fuzz.sh)";
  EXPECT_GE(replay(GetParam(), dir, false), 1u) << "no saved inputs in " << dir;
}

INSTANTIATE_TEST_SUITE_P(Loaders, FuzzRegression, testing::ValuesIn(fuzz::kLoaders),
                         [](const testing::TestParamInfo<Loader>& p) {
                           return std::string(fuzz::loader_name(p.param));
                         });

// A folder named after no loader would never be replayed (nor fuzzed by .ci/fuzz.sh).
TEST(FuzzRegression, EveryFolderNamesALoader) {
  for (const char* kind : {"corpus", "regressions"}) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(kFuzzDir / kind, ec)) {
      if (entry.is_directory()) {
        EXPECT_TRUE(fuzz::loader_from_name(entry.path().filename().string()))
            << entry.path() << " is not named after a loader (ply, obj, xml, json, pbrt)";
      } else {
        ADD_FAILURE() << entry.path() << ": inputs belong in a per-loader subfolder";
      }
    }
  }
}

}  // namespace
}  // namespace kiln
