// The sinks a run writes, opened from the output options: JSONL, MOTChallenge text, annotated frames.
// Shared by every per-frame job (detection, tracking, ...), each of which writes its own rows into them.
#pragma once

#include <optional>

#include "bodyrec/io/sinks.h"
#include "common_options.h"

namespace bodyrec::cli {

struct RunSinks {
  // Opens the sinks `outputs` names (JSONL only when `write_jsonl`); `fps` sets the annotated video's rate.
  RunSinks(const OutputOptions& outputs, bool write_jsonl, double fps) {
    if (write_jsonl) jsonl.emplace(outputs.jsonl);
    if (!outputs.mot.empty()) mot.emplace(outputs.mot);
    if (!outputs.annotate.empty()) annotated.emplace(outputs.annotate, fps);
  }
  std::optional<JsonlWriter> jsonl;
  std::optional<MotWriter> mot;
  std::optional<AnnotatedWriter> annotated;
};

}  // namespace bodyrec::cli
