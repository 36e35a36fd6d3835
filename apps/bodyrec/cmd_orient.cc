// `bodyrec orient REC|FILE.skeleton`: per frame and body, the body's yaw, its view (one of the eight
// thesis views, or none with the reason) and a confidence.
#include <cstdio>
#include <map>
#include <memory>

#include <nlohmann/json.hpp>

#include "bodyrec/io/sinks.h"
#include "command.h"
#include "orient_job.h"

namespace bodyrec::cli {
namespace {

nlohmann::json oriented_body_json(const OrientedBody& b) {
  const ViewEstimate& v = b.view;
  nlohmann::json j = {{"key", b.key},
                      {"slot", b.slot},
                      {"yaw_deg", v.has_yaw ? nlohmann::json(std::round(v.yaw_deg * 100) / 100) : nlohmann::json()},
                      {"view", v.view ? nlohmann::json(view_name(*v.view)) : nlohmann::json()},
                      {"confidence", std::round(v.confidence * 1000) / 1000},
                      {"source", v.source},
                      {"face", b.face.looked ? nlohmann::json(b.face.face) : nlohmann::json()}};
  if (!v.view) j["reason"] = v.reason;
  return j;
}

struct OrientCommand {
  std::string input, jsonl;
  OrientCliOptions options;
  bool json = false, quiet = false;

  void run() const {
    std::unique_ptr<JsonlWriter> lines;
    if (!jsonl.empty()) lines = std::make_unique<JsonlWriter>(jsonl);
    const bool text = !quiet && jsonl != "-";
    std::map<std::string, int> per_view;
    int bodies = 0, none = 0;
    double ms = 0;
    const int frames = run_orientation(input, options, [&](const OrientFrame& f) {
      nlohmann::json list = nlohmann::json::array();
      for (const OrientedBody& b : f.result.bodies) {
        ++bodies;
        const ViewEstimate& v = b.view;
        if (v.view) ++per_view[view_name(*v.view)];
        else ++none;
        if (lines) list.push_back(oriented_body_json(b));
        if (text) {
          if (v.view)
            std::printf("frame %d body %llu yaw %7.1f view %-2s confidence %.2f (%s%s)\n", f.frame.index,
                        static_cast<unsigned long long>(b.key), v.yaw_deg, view_name(*v.view), v.confidence,
                        v.source.c_str(), b.face.face ? ", face" : "");
          else
            std::printf("frame %d body %llu view none: %s\n", f.frame.index, static_cast<unsigned long long>(b.key),
                        v.reason.c_str());
        }
      }
      ms += f.result.ms;
      if (lines) lines->write({{"frame", f.frame.index}, {"time_s", f.frame.time_s}, {"bodies", list}});
    });
    const double per_body = bodies ? ms / bodies : 0.0;
    if (text) {
      std::printf("frames %d, bodies %d, no view %d, %.3f ms per body (%s)\nviews:", frames, bodies, none, per_body,
                  view_method_name(options.pipeline.orientation.method));
      for (const auto& [name, n] : per_view) std::printf(" %s %d", name.c_str(), n);
      std::printf("\n");
    }
    if (json) {
      nlohmann::json views = nlohmann::json::object();
      for (const auto& [name, n] : per_view) views[name] = n;
      std::printf("%s\n", nlohmann::json({{"frames", frames}, {"bodies", bodies}, {"no_view", none}, {"views", views},
                                          {"ms_per_body", per_body}})
                              .dump()
                              .c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<OrientCommand>();
  CLI::App* sub = app.add_subcommand("orient", "Body orientation and view (F, FR, FL, SR, SL, B, BR, BL) per frame and body");
  sub->add_option("INPUT", command->input, "Recording directory, or an NTU RGB+D .skeleton file")->required();
  add_orient_options(*sub, command->options);
  sub->add_option("--jsonl", command->jsonl,
                  "Per-frame JSON lines {frame, time_s, bodies: [{key, slot, yaw_deg, view, confidence, source, face, "
                  "reason}]}; '-' = stdout instead of the text lines");
  sub->add_flag("-q,--quiet", command->quiet, "No per-body text lines");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (frames, bodies, no_view, views, ms_per_body)");
  sub->footer(
      "Yaw: 0 = facing the camera, +90 = facing -X (the image's left), +-180 = back (src/bodyrec/reid/orientation.h).\n"
      "Example: bodyrec orient ../shared/datasets/ntu_skeleton/samples/S001C001P001R001A011.skeleton\n"
      "         bodyrec synth --people 3 --seed 2 --frames 90 --out rec -q && bodyrec orient rec --jsonl -");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 62, add});

}  // namespace
}  // namespace bodyrec::cli
