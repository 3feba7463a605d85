// Fuzz target: the study parser, as `lsi sweep STUDY.json` reaches it (io/study_parser.cpp).
//
//   bytes -> json_fields::parse_json_document -> parse_study
//
// A study's `scene` may be a file path: it is resolved against scenes/studies/
// (LSI_FUZZ_STUDY_DIR), so the shipped studies' "../former-reference/L1-B1.json" is read as `lsi sweep`
// would read it. parse_study starts Kokkos once (the sampler keeps its tables in Views); it stays
// up between inputs. Every rejection must be an lsi::InputError with a one-line message; what is
// accepted must satisfy tests/fuzz/study_invariants.hpp.
#include <string>

#include "io/json_fields.hpp"
#include "model/study.hpp"
#include "fuzz_target.hpp"
#include "study_invariants.hpp"
#include "io/study_parser.hpp"

#ifndef LSI_FUZZ_STUDY_DIR
#error \
    "LSI_FUZZ_STUDY_DIR (the directory that relative scene paths of a study start from) is not set"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = lsi::fuzz::as_text(data, size);
  lsi::fuzz::expect_only_input_errors("study", [&] {
    const nlohmann::json doc = lsi::json_fields::parse_json_document(text, "fuzz-input");
    lsi::fuzz::check_study(lsi::parse_study(doc, LSI_FUZZ_STUDY_DIR));
  });
  return 0;
}
