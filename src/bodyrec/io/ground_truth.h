// Ground-truth (and result) boxes with identities, per frame: PETS/CVML XML and MOTChallenge text.
// Frames are 0-based everywhere in bodyrec; MOTChallenge files are 1-based on disk and converted here.
#pragma once

#include <map>
#include <iosfwd>
#include <string>
#include <vector>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

struct LabelledBox {
  int frame = 0;        // 0-based
  int id = -1;          // identity, -1 when unknown
  Box box;
  double score = 1.0;   // confidence for results; 1 for ground truth
  bool ignore = false;  // MOT17 non-pedestrian classes and zero-confidence rows: neither hit nor miss
};

struct GroundTruth {
  std::vector<LabelledBox> boxes;
  int frame_count = 0;  // frames the file covers: highest frame index + 1 (CVML: every <frame> listed)

  // Boxes grouped by frame (frames without boxes are absent).
  std::map<int, std::vector<LabelledBox>> by_frame() const;
};

// PETS 2009 / CVML XML: <dataset><frame number="N"><objectlist><object id="K"><box xc yc w h/>...
// Throws InputError naming the file, frame and field for malformed XML, missing or non-numeric
// attributes, negative sizes, or a root that is not <dataset>.
GroundTruth read_cvml(const std::string& path);
// The same from XML text; `name` names the source in messages.
GroundTruth parse_cvml(const std::string& text, const std::string& name);

// MOTChallenge text: frame,id,x,y,w,h[,conf[,class[,visibility]]] (gt.txt and results alike; extra
// columns ignored). A row with conf == 0 or a class other than 1 (pedestrian), when those columns are
// present and the file is a gt file (`is_ground_truth`), is kept with ignore = true.
// Throws InputError naming the file and line for too few columns, non-numbers, frame < 1 or sizes < 0.
GroundTruth read_mot(const std::string& path, bool is_ground_truth);
// The same from a stream; `name` names the source in messages.
GroundTruth read_mot(std::istream& in, const std::string& name, bool is_ground_truth);

// Chooses by extension: .xml -> CVML, otherwise MOTChallenge text (as ground truth). A MOT file without a
// single row is an InputError ("PATH: no ground-truth rows"), as an empty CVML file is.
GroundTruth read_ground_truth(const std::string& path);

}  // namespace bodyrec
