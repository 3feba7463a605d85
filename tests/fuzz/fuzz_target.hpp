// What every fuzz target does with one input (tests/fuzz/fuzz_scene.cpp, fuzz_study.cpp).
//
// Bad input must give an lsi::InputError with a clear one-line message; anything else is a bug
// that the fuzzer must see as a crash: another exception type (nlohmann::json::type_error,
// std::out_of_range, std::bad_alloc, ...), an abort, undefined behaviour (the sanitizers of the
// libFuzzer build), or a parse that succeeds but yields a value the schema does not allow
// (checked by tests/fuzz/*_invariants.hpp). Every such bug ends in `bug()`, which prints what
// went wrong and aborts: libFuzzer then saves the input as a crash, and the standalone driver
// (tests/fuzz/fuzz_driver_main.cpp) saves it next to its working directory.
#pragma once
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <string_view>

#include "model/scene.hpp"  // lsi::InputError

namespace lsi::fuzz {

// Prints "lsi fuzz: <what>" to stderr and aborts.
[[noreturn]] void bug(const std::string& what);

// Aborts unless `condition`; `what` says which invariant failed and with which value.
inline void require(bool condition, const std::string& what) {
  if (!condition) bug("invariant violated: " + what);
}

// The message of an InputError must be one non-empty line (docs/reference/scene_schema.md). With the
// environment variable LSI_FUZZ_VERBOSE set, it is also printed (to see what a corpus exercises).
void check_error_message(const InputError& e);

// Runs `parse`; an lsi::InputError is the expected answer to bad input (its message is checked),
// any other exception is a bug.
template <class F>
void expect_only_input_errors(std::string_view target, F&& parse) {
  try {
    parse();
  } catch (const InputError& e) {
    check_error_message(e);
  } catch (const std::exception& e) {
    bug(std::string(target) +
        ": an exception other than lsi::InputError escaped the parser: " + e.what());
  } catch (...) {
    bug(std::string(target) + ": a non-standard exception escaped the parser");
  }
}

inline std::string as_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace lsi::fuzz

// The libFuzzer entry point; each fuzz target defines it once.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
