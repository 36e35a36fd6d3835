// Errors met while processing a frame name that frame: a detector or background model only knows that a
// frame's size changed, the loop knows which file or video frame it was.
#pragma once

#include <string>

#include "bodyrec/core/error.h"
#include "bodyrec/io/frame_source.h"

namespace bodyrec::cli {

// Runs `body` (the processing of `frame`) and returns what it returns. An InputError it throws that does not
// already name the frame is thrown again with the frame's name in front ("photos/b.png: foreground: frame
// size changed from 559x536 to 455x414").
template <typename Body>
decltype(auto) naming_frame(const Frame& frame, Body&& body) {
  try {
    return body();
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (frame.name.empty() || what.find(frame.name) != std::string::npos) throw;
    throw InputError(frame.name + ": " + what);
  }
}

}  // namespace bodyrec::cli
