// The fuzz target's checks (fuzz_sdl_parser.cpp, linked in) on the seed scenes and on 2000
// deterministic mutants of them, with any compiler: a few seconds of what scripts/fuzz-sdl.sh
// does for minutes under the sanitizers. The target aborts on a failed check.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sdl/sdl.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

int run_target(const std::string& input) {
  return LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size());
}

std::vector<std::string> seeds() {
  std::vector<std::string> texts;
  const std::filesystem::path root(SYNCAP_SOURCE_DIR);
  for (const auto& dir : {root / "tests/host/sdl/data", root / "docs/examples"}) {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() != ".sdl") continue;
      std::ifstream in(entry.path());
      std::stringstream text;
      text << in.rdbuf();
      texts.push_back(text.str());
    }
  }
  return texts;
}

// One mutation as libFuzzer would do: flip, insert or erase bytes, splice in a word, truncate.
std::string mutate(std::string text, std::mt19937& rng) {
  static constexpr std::array<const char*, 12> kWords{"include \"self.sdl\"",
                                                      "include \"other.sdl\"",
                                                      "}",
                                                      "{",
                                                      "<",
                                                      "/ 0",
                                                      "1e308 * 10",
                                                      "NO ",
                                                      "\"",
                                                      "/*",
                                                      "declare x = ",
                                                      "SIMULATE"};
  const auto at = [&](size_t n) { return std::uniform_int_distribution<size_t>(0, n)(rng); };
  switch (at(4)) {
    case 0:
      if (!text.empty()) text[at(text.size() - 1)] ^= static_cast<char>(1 << at(7));
      break;
    case 1:
      text.insert(at(text.size()), kWords[at(kWords.size() - 1)]);
      break;
    case 2:
      if (!text.empty()) text.erase(at(text.size() - 1), at(16));
      break;
    case 3:
      text.resize(at(text.size()));
      break;
    default:
      text.insert(at(text.size()), 1, static_cast<char>(at(255)));
      break;
  }
  return text;
}

TEST(SdlFuzzSmoke, SeedsAndTheirMutantsPassTheTargetsChecks) {
  const std::vector<std::string> texts = seeds();
  ASSERT_GE(texts.size(), 2u);
  for (const std::string& text : texts) EXPECT_EQ(run_target(text), 0);
  std::mt19937 rng(2026);
  int parsed = 0;
  for (int i = 0; i < 2000; ++i) {
    std::string mutant = texts[static_cast<size_t>(i) % texts.size()];
    for (int k = 0; k < 1 + i % 4; ++k) mutant = mutate(mutant, rng);
    EXPECT_EQ(run_target(mutant), 0);
    try {
      syncap::sdl::parse_string(mutant, "/nonexistent/mutant.sdl");
      ++parsed;  // the round trip was checked on this one
    } catch (const syncap::sdl::ParseError&) {
    }
  }
  EXPECT_GT(parsed, 50) << "too few mutants parse to test the round trip";
}

}  // namespace
