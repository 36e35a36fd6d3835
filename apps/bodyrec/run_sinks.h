// The sinks a run writes, opened from the output options: JSONL, MOTChallenge text, annotated frames.
// Shared by every per-frame job (detection, tracking, ...), each of which writes its own rows into them.
#pragma once

#include <cstdio>
#include <optional>
#include <string>

#include "bodyrec/io/sinks.h"
#include "common_options.h"

namespace bodyrec::cli {

// Writes "bodyrec: note: NOTE" on stderr unless `note` is empty (FrameFolder::stale_note).
inline void note_stale_frames(const std::string& note) {
  if (!note.empty()) std::fprintf(stderr, "bodyrec: note: %s\n", note.c_str());
}

struct RunSinks {
  // Opens the sinks `outputs` names (JSONL only when `write_jsonl`); `fps` sets the annotated video's rate.
  RunSinks(const OutputOptions& outputs, bool write_jsonl, double fps) {
    if (write_jsonl) jsonl.emplace(outputs.jsonl);
    if (!outputs.mot.empty()) mot.emplace(outputs.mot);
    if (!outputs.annotate.empty()) annotated.emplace(outputs.annotate, fps);
  }
  // At the end of a run: a line on stderr when the annotated frames' folder still holds frames of an
  // earlier run (a shorter run leaves the earlier run's later frames beside its own).
  void note_stale() const {
    if (annotated) note_stale_frames(annotated->stale_note());
  }

  std::optional<JsonlWriter> jsonl;
  std::optional<MotWriter> mot;
  std::optional<AnnotatedWriter> annotated;
};

}  // namespace bodyrec::cli
