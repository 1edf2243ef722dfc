// The short seeded run of a fuzz target in the normal suite (no libFuzzer needed): feeds
// LLVMFuzzerTestOneInput every file of the given corpus folders, then a fixed number of
// deterministic mutations of them (fixed seed, so every run tests the same inputs).
// Usage: fuzz_replay_<target> [--mutations N] [--seed S] DIR_OR_FILE...

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "stitchsim/common/files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

// splitmix64: the same sequence on every platform and standard library.
struct Rng {
  std::uint64_t state;
  std::uint64_t Next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::size_t Below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(Next() % n); }
};

// Tokens that reach the readers' edge cases faster than random bytes do.
constexpr std::string_view kTokens[] = {
    "0",
    "-1",
    "1e300",
    "-1e300",
    "6e36",
    "2147483648",
    "-2147483649",
    "99999999999999999999",
    "nan",
    "inf",
    ".",
    "\n",
    "\r\n",
    "%",
    "(",
    ")",
    ";",
    ":",
    "- ",
    "[",
    "]",
    "{",
    "}",
    "\"",
    "'",
    "&a",
    "*a",
    "!!",
    "~",
    "0x10",
    "1e-320",
    "\t",
    " ",
    "\xff",
    std::string_view("\0", 1),
};

std::string Mutate(const std::vector<std::string>& corpus, Rng& rng) {
  std::string s = corpus[rng.Below(corpus.size())];
  const std::size_t edits = 1 + rng.Below(4);
  for (std::size_t e = 0; e < edits; ++e) {
    const std::size_t at = rng.Below(s.size() + 1);
    switch (rng.Below(6)) {
      case 0:  // flip a byte
        if (!s.empty()) s[std::min(at, s.size() - 1)] ^= static_cast<char>(1 + rng.Below(255));
        break;
      case 1:  // insert a token
        s.insert(at, kTokens[rng.Below(std::size(kTokens))]);
        break;
      case 2:  // erase a run
        s.erase(at, 1 + rng.Below(16));
        break;
      case 3:  // repeat a run
        s.insert(at, s.substr(at, 1 + rng.Below(32)));
        break;
      case 4:  // truncate
        s.resize(at);
        break;
      default: {  // splice another input's tail
        const std::string& other = corpus[rng.Below(corpus.size())];
        s = s.substr(0, at) + other.substr(rng.Below(other.size() + 1));
      }
    }
  }
  return s;
}

void Run(const std::string& input) {
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
}

}  // namespace

int main(int argc, char** argv) {
  long mutations = 2000;
  std::uint64_t seed = 20261123;
  std::vector<std::string> corpus;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--mutations" && i + 1 < argc) {
      mutations = std::strtol(argv[++i], nullptr, 10);
    } else if (arg == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else {
      std::vector<std::filesystem::path> files;
      if (std::filesystem::is_directory(arg)) {
        for (const auto& entry : std::filesystem::recursive_directory_iterator(arg)) {
          if (entry.is_regular_file()) files.push_back(entry.path());
        }
        std::sort(files.begin(), files.end());
      } else {
        files.push_back(arg);
      }
      for (const auto& f : files) {
        auto text = stitchsim::ReadFile(f);
        if (!text) {
          std::fprintf(stderr, "cannot read corpus file %s\n", f.string().c_str());
          return 2;
        }
        corpus.push_back(std::move(*text));
      }
    }
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "usage: %s [--mutations N] [--seed S] DIR_OR_FILE...\n", argv[0]);
    return 2;
  }
  for (const std::string& input : corpus) Run(input);
  Rng rng{seed};
  for (long i = 0; i < mutations; ++i) Run(Mutate(corpus, rng));
  std::printf("%zu corpus inputs and %ld mutations (seed %llu) ran clean\n", corpus.size(),
              mutations, static_cast<unsigned long long>(seed));
  return 0;
}
