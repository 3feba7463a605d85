// The libFuzzer custom mutator (libFuzzer build only, tests/fuzz/CMakeLists.txt): half of the
// mutations are libFuzzer's own (byte edits, the dictionary tests/fuzz/lsi.dict, corpus
// cross-over), half the JSON-aware edits of json_mutator.hpp. Byte edits of a JSON text mostly
// break its syntax; the JSON-aware edits keep it a scene or a study with one value out of range,
// a key missing or repeated, a type changed, which is what the parsers' checks are about.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "json_mutator.hpp"

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size,
                                               std::size_t max_size, unsigned int seed) {
  if (seed % 2 == 0) return LLVMFuzzerMutate(data, size, max_size);
  const std::string text(reinterpret_cast<const char*>(data), size);
  // The input is its own cross-over donor (values moved between its keys); libFuzzer's mutations
  // cross inputs of the corpus.
  lsi::fuzz::JsonMutator mutator({text}, seed);
  const std::string mutant = mutator.mutate(text);
  if (mutant.size() > max_size || mutant == text) return LLVMFuzzerMutate(data, size, max_size);
  std::memcpy(data, mutant.data(), mutant.size());
  return mutant.size();
}
