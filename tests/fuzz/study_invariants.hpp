// What a successfully parsed study must satisfy (docs/reference/scene_schema.md, "Study files"): a valid
// base scene, 1 to 32 inputs on distinct sampleable paths with valid, finite distributions,
// counts and levels in their ranges, methods and outputs out of the allowed lists, rules that
// refer to them, and samples that can be turned into scenes: the first samples the sampler draws
// go through sample_scene_document / invalid_sample_reason (what `lsi sweep` does with every
// sample) without any exception other than lsi::InputError. A violation calls lsi::fuzz::bug.
#pragma once
#include "model/study.hpp"
#include "io/study_parser.hpp"

namespace lsi::fuzz {

void check_study(const Study& study);

}  // namespace lsi::fuzz
