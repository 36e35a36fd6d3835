// A folder a run fills with one file per frame (annotated frames, label masks, cut-outs), named by the
// frame number in 6 digits: NNNNNN.png, or NNNNNN<tag>.png for several files per frame.
//
// Files of that pattern already in the folder come from an earlier run. A shorter run into the same
// folder overwrites the earlier run's first frames only and leaves its later ones beside its own: the
// folder counts them, so that the caller can say so. Nothing is deleted: the folder may hold what a
// user put there.
#pragma once

#include <set>
#include <string>

namespace bodyrec {

class FrameFolder {
 public:
  // Creates `dir` when missing (ProcessingError when it cannot) and notes the frame files in it.
  explicit FrameFolder(std::string dir);

  // DIR/NNNNNN<tag>.png for `frame`, noted as written by this run.
  std::string file(int frame, const std::string& tag = "");

  // Frame files found at opening that this run has not written again: an earlier run's.
  size_t stale() const;
  // "DIR holds N frame files of an earlier run that this run did not replace (FIRST ... LAST)", or "" when
  // there are none.
  std::string stale_note() const;

  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::set<std::string> earlier_, written_;  // file names
};

// "000042": the zero-padded file stem of frame 42 (frame folders, recordings).
std::string frame_stem(int index);

// True when `name` is a frame file name: 6 digits, then optionally more, ending ".png".
bool is_frame_file_name(const std::string& name);

}  // namespace bodyrec
