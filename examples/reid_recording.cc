// Re-identification over an RGB-D recording with a persistent gallery (thesis Ch6): every body is
// enrolled as a new user or recognised as a known one; run it twice on the same gallery and the people
// are recognised the second time.
//
//   bodyrec synth --scenario reenter --people 3 --frames 150 --out rec -q
//   reid_recording rec gallery.db
#include <cstdio>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/gallery_reid_store.h"
#include "bodyrec/reid/reid_pipeline.h"
#include "bodyrec/rgbd/recording.h"

int main(int argc, char** argv) try {
  if (argc < 3) {
    std::fprintf(stderr, "usage: reid_recording RECORDING GALLERY.db\n");
    return 2;
  }
  bodyrec::RecordingReader recording(argv[1]);
  bodyrec::GalleryOptions gallery_options;
  gallery_options.create = true;
  bodyrec::Gallery gallery(argv[2], gallery_options);
  // Colour in bands of height above the floor: needs no trained model.
  const auto matcher = bodyrec::make_matcher("stripes");
  bodyrec::GalleryReidStore store(gallery, *matcher, {argv[1], std::nullopt});
  // Bodies from the recording's skeletons, body index or depth, whichever it has (a recording with depth
  // only needs a DepthSegmenter: see bodyrec/rgbd/segment.h).
  bodyrec::ReidPipeline reid(recording.meta(), store, *matcher, {}, std::nullopt, argv[1]);

  for (bodyrec::RgbdFrame frame; recording.read(frame);) {
    const bodyrec::ReidResult r = reid.process(frame);
    for (const bodyrec::ReidEvent& e : r.step.events)
      std::printf("frame %d: user %lld %s\n", frame.index, static_cast<long long>(e.user),
                  bodyrec::reid_event_name(e.kind));
  }
  for (const bodyrec::ReidEvent& e : reid.finish())
    std::printf("end: user %lld %s\n", static_cast<long long>(e.user), bodyrec::reid_event_name(e.kind));
  std::printf("gallery %s: %d users\n", argv[2], gallery.user_count());
  return 0;
} catch (const bodyrec::Error& e) {
  std::fprintf(stderr, "reid_recording: %s\n", e.what());
  return static_cast<int>(e.code());
}
