// Groups, leaders and passers-by in a video (thesis Ch4): people detection, tracking, then who walks with
// whom and who leads, frame by frame.
//
//   groups_on_video /usr/share/doc/opencv-doc/examples/data/vtest.avi
#include <cstdio>

#include "bodyrec/core/error.h"
#include "bodyrec/detection/hog_people_detector.h"
#include "bodyrec/groups/group_pipeline.h"
#include "bodyrec/io/frame_source.h"

int main(int argc, char** argv) try {
  bodyrec::SourceOptions source_options;
  source_options.path = argc > 1 ? argv[1] : "/usr/share/doc/opencv-doc/examples/data/vtest.avi";
  source_options.max_frames = 100;
  const auto source = bodyrec::open_source(source_options);

  // OpenCV's HOG people detector, searched around moving regions (a fixed camera).
  bodyrec::HogPeopleDetector detector(bodyrec::hog_preset(bodyrec::HogPreset::kDefault));
  bodyrec::GroupPipelineOptions options;
  options.fps = 7;  // vtest.avi was recorded at 7 frames per second (its header says 10)
  // No ground plane: distances in pixels, scaled by the people's box heights.
  bodyrec::GroupPipeline groups(detector, options, nullptr);

  int leaders = 0, frames = 0;
  for (bodyrec::Frame frame; source->read(frame); ++frames) {
    const bodyrec::GroupPipelineResult r = groups.process(frame);
    leaders += static_cast<int>(r.groups.leaders.size());
    for (const bodyrec::PersonView& p : r.groups.people)
      if (frame.index % 25 == 0)
        std::printf("frame %d: person %d %s%s\n", frame.index, p.id, bodyrec::to_string(p.role).c_str(),
                    p.group >= 0 ? (" of group " + std::to_string(p.group)).c_str() : "");
  }
  std::printf("%d frames, %d leader-frames\n", frames, leaders);
  return 0;
} catch (const bodyrec::Error& e) {
  std::fprintf(stderr, "groups_on_video: %s\n", e.what());
  return static_cast<int>(e.code());
}
