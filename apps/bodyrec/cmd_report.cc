// `bodyrec report`: one self-contained HTML page about a run (and its evaluations) that people can look at.
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>

#include "bodyrec/core/error.h"
#include "bodyrec/io/frame_source.h"
#include "bodyrec/rgbd/recording.h"
#include "bodyrec/report/gallery_users.h"
#include "bodyrec/report/report.h"
#include "command.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct ReportCommand {
  std::string run_path, source, gallery, out;
  std::vector<std::string> evals;
  int key_frames = 5;
  bool no_images = false;

  // Decodes the chosen frames of the source (a video, images or a camera's frames as `detect` reads them, or
  // a recording's colour frames) and draws the run's boxes on them.
  std::vector<report::KeyFrame> decode_key_frames(const report::RunData& run) const {
    std::vector<report::KeyFrame> frames;
    const auto chosen = report::choose_key_frames(run, key_frames);
    if (chosen.empty()) return frames;
    const auto add = [&](int index, const cv::Mat& image) {
      report::KeyFrame k;
      k.frame = index;
      k.image = image.clone();
      k.caption = report::annotate_key_frame(k.image, run, index);
      frames.push_back(std::move(k));
    };
    const auto ends_before = [&](int index) {
      return InputError(source + ": ends before frame " + std::to_string(index) + " of " + run_path +
                        " (is it the run's input?)");
    };
    if (is_recording_directory(source)) {
      const RecordingReader recording(source);
      if (!recording.meta().streams.color) throw InputError(source + ": the recording has no colour frames to show");
      for (int index : chosen) {
        if (index >= recording.frame_count()) throw ends_before(index);
        add(index, recording.read_frame(index).color);
      }
      return frames;
    }
    SourceOptions options;
    options.path = source;
    auto video = open_source(options);
    Frame frame;
    size_t next = 0;
    while (next < chosen.size() && video->read(frame)) {
      if (frame.index != chosen[next]) continue;
      add(frame.index, frame.image);
      ++next;
    }
    if (next < chosen.size()) throw ends_before(chosen[next]);
    return frames;
  }

  void run() const {
    report::ReportInput input;
    input.run = report::read_run(run_path);
    for (const auto& e : evals) input.evals.push_back(report::read_eval(e));
    input.source = source;
    input.images = !no_images;
    // Read-only: a bad gallery fails here, before anything is written.
    if (!gallery.empty()) {
      input.users = report::read_gallery_users(gallery, input.images);
      input.have_gallery = true;
    }
    const std::time_t now = std::time(nullptr);
    char stamp[32];
    std::strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    input.generated = stamp;
    if (!source.empty() && input.images) input.key_frames = decode_key_frames(input.run);
    const std::string page = report::render_report(input);
    std::ofstream file(out, std::ios::binary);
    if (!file) throw ProcessingError(out + ": cannot write the report");
    // The page shows people and their identities: private (0600) whatever the umask, like the gallery.
    std::error_code ec;
    std::filesystem::permissions(out, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write, ec);
    if (ec) throw ProcessingError(out + ": cannot make the report private (" + ec.message() + ")");
    if (!(file << page) || !file.flush()) throw ProcessingError(out + ": cannot write the report");
    std::printf("bodyrec: wrote %s (%zu KB; %s run, %d frames, %zu evaluations, %zu key frames%s)\n", out.c_str(),
                page.size() / 1024, report::to_string(input.run.kind), input.run.frame_count(), input.evals.size(),
                input.key_frames.size(),
                input.have_gallery ? (", " + std::to_string(input.users.size()) + " gallery users").c_str() : "");
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<ReportCommand>();
  CLI::App* sub = app.add_subcommand("report", "Write one self-contained HTML page about a run and its evaluations");
  sub->footer(
      "The page embeds everything (inline CSS and SVG plots, JPEG images as data URIs): no scripts, nothing\n"
      "loaded from the network. It shows images of people unless --no-images is given, and is written\n"
      "private (mode 0600) whatever the umask, as the gallery is.\n"
      "--gallery adds one row per gallery user: id, label, first/last seen (UTC), the 8 partial-scan views\n"
      "(F FR FL SR SL B BR BL; dashed = no scan, hatched = scan without an image) and, for users this run has\n"
      "no events for, the gallery's own events. The gallery is only read.\n"
      "Example: bodyrec report out/groups.jsonl --source /usr/share/doc/opencv-doc/examples/data/vtest.avi "
      "--out out/report.html\n"
      "         bodyrec report run.jsonl --eval viper.json --eval hotel.json --out report.html\n"
      "         bodyrec report reid.jsonl --gallery gallery.db --out report.html");
  sub->add_option("run", command->run_path, "Run JSON lines (bodyrec groups --jsonl, bodyrec reid)")->required();
  sub->add_option("--source", command->source,
                  "The run's input (a video, an image folder or glob, or an RGB-D recording): key frames are "
                  "decoded from it and annotated");
  sub->add_option("--eval", command->evals,
                  "File holding the --json output of an eval command (kind from its keys); repeatable. Per-person "
                  "landmark errors (eval landmarks --per-person) give a histogram");
  sub->add_option("--gallery", command->gallery,
                  "Gallery (read-only; SQLite file or postgresql:// URI): a row per user with their 8 views, "
                  "first/last seen, events");
  sub->add_option("--key-frames", command->key_frames, "How many key frames to show")->check(in_range(0, 12));
  sub->add_flag("--no-images", command->no_images, "Leave every image of a person out of the page");
  sub->add_option("--out", command->out, "The HTML file to write")->required();
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 200, add});

}  // namespace
}  // namespace bodyrec::cli
