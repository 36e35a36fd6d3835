#include "fuzz_targets.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include <nlohmann/json.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "bodyrec/core/error.h"
#include "bodyrec/events/event_spool.h"
#include "bodyrec/events/mqtt_target.h"
#include "bodyrec/groups/walking_scene.h"
#include "bodyrec/io/ground_plane.h"
#include "bodyrec/io/ground_truth.h"
#include "bodyrec/io/imglab_xml.h"
#include "bodyrec/io/roles_csv.h"
#include "bodyrec/rgbd/ntu_skeleton.h"
#include "bodyrec/rgbd/pcd.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec::fuzz {
namespace {

std::string text_of(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

// Runs `parse`; a typed bodyrec error is the expected answer to bad input, anything else propagates.
template <class F>
int typed_errors_only(F&& parse) {
  try {
    parse();
  } catch (const Error&) {
  }
  return 0;
}

}  // namespace

int fuzz_cvml(const uint8_t* data, size_t size) {
  return typed_errors_only([&] { parse_cvml(text_of(data, size), "fuzz.xml"); });
}

int fuzz_mot(const uint8_t* data, size_t size) {
  for (const bool gt : {true, false}) {
    typed_errors_only([&] {
      std::istringstream in(text_of(data, size));
      read_mot(in, "fuzz.txt", gt);
    });
  }
  return 0;
}

int fuzz_imglab(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    const ImglabDataset d = parse_imglab(text_of(data, size), "fuzz.xml");
    for (const auto& image : d.images)
      for (const auto& box : image.boxes) typed_errors_only([&] { ordered_parts(box, image.file); });
  });
}

int fuzz_roles_csv(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    std::istringstream in(text_of(data, size));
    read_roles_csv(in, "fuzz.csv");
  });
}

int fuzz_homography(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    std::istringstream in(text_of(data, size));
    const auto plane = read_homography(in, "fuzz.txt");
    plane->to_ground({100, 200});
    plane->describe();
  });
}

int fuzz_tsai(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    const auto plane = parse_tsai_calibration(text_of(data, size), "fuzz.xml");
    plane->to_ground({100, 200});
    plane->describe();
  });
}

int fuzz_ntu_skeleton(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    std::istringstream in(text_of(data, size));
    const NtuSkeleton s = read_ntu_skeleton(in, "fuzz.skeleton");
    RecordingMeta meta;
    double rms[2];
    fit_ntu_cameras(s, meta, rms);
  });
}

int fuzz_pcd(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    std::istringstream in(text_of(data, size), std::ios::binary);
    const PcdCloud cloud = read_pcd(in, "fuzz.pcd");
    fit_pcd_intrinsics(cloud, "fuzz.pcd");
  });
}

int fuzz_recording_meta(const uint8_t* data, size_t size) {
  return typed_errors_only([&] { meta_from_json(parse_json_text(text_of(data, size), "meta.json"), "meta.json"); });
}

int fuzz_recording_bodies(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    const auto j = parse_json_text(text_of(data, size), "bodies/000000.json");
    typed_errors_only([&] {
      check_joint_positions(bodies_from_json(j, "bodies/000000.json"), kinect2_depth_intrinsics(), "bodies/000000.json");
    });
    typed_errors_only([&] { truth_from_json(j, "truth/000000.json"); });
  });
}

int fuzz_obsmat(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    std::istringstream in(text_of(data, size));
    const auto rows = read_obsmat(in, "obsmat.txt");
    // Its contract: a finite, positive period or an InputError; anything else is a finding.
    const double period = estimate_seconds_per_frame(rows, "obsmat.txt");
    if (!(period > 0 && std::isfinite(period))) std::abort();
  });
}

int fuzz_groups(const uint8_t* data, size_t size) {
  return typed_errors_only([&] {
    std::istringstream in(text_of(data, size));
    read_groups(in, "groups.txt");
  });
}

namespace {

// A private scratch file for the parsers that read files: its path, removed with its side files.
struct ScratchFile {
  std::string path;
  explicit ScratchFile(const std::string& name, const uint8_t* data, size_t size) {
    path = (std::filesystem::temp_directory_path() / ("bodyrec-fuzz-" + std::to_string(::getpid()) + "-" + name)).string();
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    ::chmod(path.c_str(), 0600);
  }
  ~ScratchFile() {
    for (const char* suffix : {"", ".sent", ".tmp", ".sent.tmp"}) std::remove((path + suffix).c_str());
  }
};

}  // namespace

int fuzz_event_spool(const uint8_t* data, size_t size) {
  ScratchFile file("spool", data, size);
  return typed_errors_only([&] {
    EventSpool spool(file.path, 50);
    for (int i = 0; i < 3 && !spool.empty(); ++i) spool.pop();
    spool.push({"t/a/reid", "{}"});
  });
}

int fuzz_mqtt_uri(const uint8_t* data, size_t size) {
  const std::string text = text_of(data, size);
  typed_errors_only([&] { parse_mqtt_uri(text.substr(0, text.find('\n'))); });
  ScratchFile file("credentials", data, size);
  return typed_errors_only([&] { read_mqtt_credentials(file.path); });
}

const std::vector<NamedTarget>& all_targets() {
  static const std::vector<NamedTarget> targets = {
      {"cvml", fuzz_cvml},
      {"mot", fuzz_mot},
      {"imglab", fuzz_imglab},
      {"roles_csv", fuzz_roles_csv},
      {"homography", fuzz_homography},
      {"tsai", fuzz_tsai},
      {"ntu_skeleton", fuzz_ntu_skeleton},
      {"pcd", fuzz_pcd},
      {"recording_meta", fuzz_recording_meta},
      {"recording_bodies", fuzz_recording_bodies},
      {"obsmat", fuzz_obsmat},
      {"groups", fuzz_groups},
      {"event_spool", fuzz_event_spool},
      {"mqtt_uri", fuzz_mqtt_uri},
  };
  return targets;
}

}  // namespace bodyrec::fuzz
