// Deterministic mutants of JSON seed inputs, for the standalone fuzz driver
// (tests/fuzz/fuzz_driver_main.cpp): the bounded, reproducible counterpart of a libFuzzer campaign
// that runs in every `ctest`. Same seed, same seeds in the same order -> the same mutants, on any
// machine (a 64-bit xorshift generator, no std:: distributions).
//
// A mutant is one to three JSON-aware edits of a seed, sometimes followed by a byte-level edit:
//   JSON-aware (on the parsed seed, written back as text):
//     - a value replaced by a "nasty" literal: NaN, Infinity, -Infinity, 1e999, 1e308, -1e308,
//       5e-324, 0, -0, -1, 1, 0.5, 2.5, 64, 1e6, huge integers (2^63, 2^64, -2^63 - 1),
//       "12", "", true, null, [], {}, [1, 2], {"a": 1}
//     - a string replaced by another one the parsers give a meaning to (enum values, JSON
//       pointers of study inputs, malformed pointers, scene file paths) or edited
//     - an object member deleted, duplicated (same key twice), or an unknown key added
//     - an array element deleted or duplicated, an array emptied or grown to 40 elements
//     - a value wrapped in an array or object, or in 10 to 100000 levels of nesting
//     - a value replaced by a value of another seed (crossover)
//   byte-level: bit flip, byte set to a JSON metacharacter or an invalid UTF-8 byte, a range
//   deleted, duplicated or inserted, truncation.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace lsi::fuzz {

class JsonMutator {
 public:
  // `seeds`: the inputs to mutate (raw text; those that are not JSON get byte-level edits only),
  // also the donors of the crossover edits.
  JsonMutator(std::vector<std::string> seeds, std::uint64_t random_seed);

  // The next mutant of a seed.
  std::string next();
  // A mutant of `text` (what the libFuzzer custom mutator asks for).
  std::string mutate(std::string text);

 private:
  std::uint64_t random();
  std::size_t below(std::size_t n);  // uniform enough in [0, n), n > 0
  bool chance(int percent);
  std::string json_edit(const std::string& text);
  std::string byte_edit(std::string text);

  std::vector<std::string> seeds_;
  std::uint64_t state_;
};

}  // namespace lsi::fuzz
