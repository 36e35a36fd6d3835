// `bodyrec import ntu|pcd`: converts other RGB-D data into the bodyrec recording format
// (docs/recording-format.md).
#include <cstdio>

#include <nlohmann/json.hpp>

#include "bodyrec/io/json_numbers.h"
#include "bodyrec/rgbd/ntu_skeleton.h"
#include "bodyrec/rgbd/pcd.h"
#include "command.h"

namespace bodyrec::cli {
namespace {

struct ImportCommand {
  std::string input, out;
  bool json = false;
};

void add(CLI::App& app) {
  CLI::App* import = app.add_subcommand("import", "Convert NTU RGB+D skeletons or PCD clouds into a recording");
  import->require_subcommand(1);
  import->footer("Example: bodyrec import ntu ../shared/datasets/ntu_skeleton/samples/S001C001P001R001A050.skeleton "
                 "--out rec_ntu");

  auto ntu = std::make_shared<ImportCommand>();
  CLI::App* sub = import->add_subcommand("ntu", "NTU RGB+D .skeleton text (Kinect v2 bodies; no images)");
  sub->add_option("FILE", ntu->input, "The .skeleton file")->required();
  sub->add_option("--out", ntu->out, "Recording directory to create (must not exist or be empty)")->required();
  sub->add_flag("--json", ntu->json, "End stdout with one JSON object (frames, bodies, depth_fit_rms_px, color_fit_rms_px)");
  sub->footer("Writes a bodies-only recording; depth and colour intrinsics are fitted to the joints' own "
              "projections.\nExample: bodyrec import ntu S001C001P001R001A050.skeleton --out rec_ntu --json");
  sub->callback([ntu] {
    double rms[2];
    const int frames = import_ntu(ntu->input, ntu->out, rms);
    RecordingReader reader(ntu->out);
    int max_bodies = 0;
    for (RgbdFrame f; reader.read(f);) max_bodies = std::max(max_bodies, static_cast<int>(f.bodies.size()));
    std::printf("wrote %s: %d frames, up to %d bodies per frame; intrinsics fit rms %.2f px depth, %.2f px colour\n",
                ntu->out.c_str(), frames, max_bodies, rms[0], rms[1]);
    if (ntu->json) {
      const nlohmann::json j = {{"frames", frames}, {"bodies", max_bodies}, {"depth_fit_rms_px", rms[0]},
                                {"color_fit_rms_px", rms[1]}};
      std::printf("%s\n", json_text(j).c_str());
    }
  });

  auto pcd = std::make_shared<ImportCommand>();
  sub = import->add_subcommand("pcd", "Organised XYZRGB(A) PCD cloud (ascii, binary or binary_compressed)");
  sub->add_option("FILE", pcd->input, "The .pcd file")->required();
  sub->add_option("--out", pcd->out, "Recording directory to create (must not exist or be empty)")->required();
  sub->add_flag("--json", pcd->json, "End stdout with one JSON object (width, height, fx, fy, cx, cy, valid_depth, fit_rms_px)");
  sub->footer("Writes a one-frame recording with registered colour and depth (mm).\n"
              "Example: bodyrec import pcd ../shared/datasets/pcl_people_rgbd/five_people.pcd --out rec_pcd");
  sub->callback([pcd] {
    double rms = 0;
    const Intrinsics k = import_pcd(pcd->input, pcd->out, &rms);
    RecordingReader reader(pcd->out);
    const RgbdFrame f = reader.read_frame(0);
    const int valid = cv::countNonZero(f.depth);
    std::printf("wrote %s: 1 frame %dx%d, %d pixels with depth; fitted fx %.2f fy %.2f cx %.2f cy %.2f (rms %.3f px)\n",
                pcd->out.c_str(), k.width, k.height, valid, k.fx, k.fy, k.cx, k.cy, rms);
    if (pcd->json) {
      const nlohmann::json j = {{"width", k.width}, {"height", k.height}, {"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx},
                                {"cy", k.cy}, {"valid_depth", valid}, {"fit_rms_px", rms}};
      std::printf("%s\n", json_text(j).c_str());
    }
  });
}

const bool registered = register_command({"", 50, add});

}  // namespace
}  // namespace bodyrec::cli
