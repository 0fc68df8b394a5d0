// A fuzz target's checks (its fuzz_<name>.cpp, linked in) on the target's seed corpus and on a
// few thousand deterministic mutants of it, with any compiler and without libFuzzer: seconds of
// what scripts/fuzz.sh does for minutes under the sanitizers. The target aborts on a failed
// check, so a finding kills this test. Built once per target (tests/fuzz/CMakeLists.txt), with
// SYNCAP_FUZZ_CORPUS the seed folder and SYNCAP_FUZZ_SUITE the test suite's name.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

constexpr int kMutants = 3000;

// With SYNCAP_FUZZ_SAVE=FILE set, each input is written to FILE before it runs: after a failed
// check (an abort) FILE holds the input that failed, to replay with the libFuzzer program.
int run_target(const std::string& input) {
  if (const char* save = std::getenv("SYNCAP_FUZZ_SAVE")) {
    std::ofstream(save, std::ios::binary) << input;
  }
  return LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(input.data()), input.size());
}

std::vector<std::string> seeds() {
  std::vector<std::string> inputs;
  for (const auto& entry : std::filesystem::directory_iterator(SYNCAP_FUZZ_CORPUS)) {
    std::ifstream in(entry.path(), std::ios::binary);
    inputs.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  std::sort(inputs.begin(), inputs.end());  // directory order is not deterministic
  return inputs;
}

// One mutation as libFuzzer would do: flip a bit, insert or overwrite with an interesting value,
// erase, truncate, duplicate a stretch, or splice in a stretch of another seed.
std::string mutate(std::string input, const std::vector<std::string>& others, std::mt19937& rng) {
  static constexpr std::array<std::string_view, 10> kInteresting{std::string_view("\x00", 1),
                                                                 "\xff",
                                                                 "\x7f",
                                                                 "\x80",
                                                                 "\xff\xff\xff\xff",
                                                                 "-1",
                                                                 "1e999",
                                                                 "nan",
                                                                 "\n",
                                                                 "9999999999"};
  const auto at = [&](std::size_t n) { return std::uniform_int_distribution<size_t>(0, n)(rng); };
  const std::string_view word = kInteresting[at(kInteresting.size() - 1)];
  switch (at(6)) {
    case 0:
      if (!input.empty()) input[at(input.size() - 1)] ^= static_cast<char>(1 << at(7));
      break;
    case 1:
      input.insert(at(input.size()), word);
      break;
    case 2:
      if (input.size() >= word.size())
        input.replace(at(input.size() - word.size()), word.size(), word);
      break;
    case 3:
      if (!input.empty()) input.erase(at(input.size() - 1), 1 + at(15));
      break;
    case 4:
      input.resize(at(input.size()));
      break;
    case 5:
      if (!input.empty()) {
        const std::size_t from = at(input.size() - 1);
        input.insert(at(input.size()), input.substr(from, 1 + at(31)));
      }
      break;
    default: {
      const std::string& other = others[at(others.size() - 1)];
      if (!other.empty())
        input.insert(at(input.size()), other.substr(at(other.size() - 1), 1 + at(63)));
      break;
    }
  }
  return input;
}

TEST(SYNCAP_FUZZ_SUITE, SeedsAndTheirMutantsPassTheTargetsChecks) {
  const std::vector<std::string> inputs = seeds();
  ASSERT_GE(inputs.size(), 2u) << "seed corpus " << SYNCAP_FUZZ_CORPUS;
  for (const std::string& input : inputs) EXPECT_EQ(run_target(input), 0);
  std::mt19937 rng(2026);
  for (int i = 0; i < kMutants; ++i) {
    std::string mutant = inputs[static_cast<std::size_t>(i) % inputs.size()];
    for (int k = 0; k < 1 + i % 4; ++k) mutant = mutate(mutant, inputs, rng);
    EXPECT_EQ(run_target(mutant), 0);
  }
}

}  // namespace
