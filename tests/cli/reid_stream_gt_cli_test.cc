// `eval reid-stream VIDEO --gt FILE`: plain-camera re-identification scored against a ground-truth file of
// boxes and person ids (PETS/CVML XML or MOTChallenge text), one walking figure.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"
#include "walking_figure.h"

namespace bodyrec::testing {
namespace {

// MOTChallenge ground truth of the walking figure (1-based frames), person `id` throughout; `shift` moves
// every row that many frames later (a file numbered from 0 by mistake), `dx` every box sideways.
std::string figure_truth(int id, int shift = 0, int dx = 0) {
  std::string text;
  for (int f = 0; f < 40; ++f)
    text += std::to_string(f + 1 + shift) + "," + std::to_string(id) + "," + std::to_string(20 + 5 * f + dx) +
            ",100,30,90,1,1,1\n";
  return text;
}

TEST(ReidStreamGtCli, ScoresAVideoAgainstItsGroundTruth) {
  TempDir dir;
  const std::string video = walking_figure_video(dir / "figure.avi").string(), gt = (dir / "gt.txt").string();
  write_text(gt, figure_truth(7));
  const std::string jsonl = (dir / "out.jsonl").string();
  const RunResult r = run_bodyrec({"eval", "reid-stream", video, "--gt", gt, "--json", "--jsonl", jsonl});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int people = 0;
  for (const std::string& line : lines_of(read_text(jsonl))) {
    const nlohmann::json frame = nlohmann::json::parse(line);
    for (const auto& body : frame["bodies"]) people += body["person"] == 7;
  }
  const auto s = last_json_line(r.out);
  EXPECT_EQ(s["frames"].get<int>(), 40);
  EXPECT_EQ(s["identities"].get<int>(), 1);
  EXPECT_EQ(s["users"].get<int>(), 1);
  EXPECT_EQ(s["splits"].get<int>(), 0);
  EXPECT_EQ(s["merges"].get<int>(), 0);
  EXPECT_GE(s["body_frames"].get<int>(), 18);  // after the background model's warm-up and the track's confirmation
  EXPECT_DOUBLE_EQ(s["accuracy"].get<double>(), 1.0);
  EXPECT_TRUE(s["colour_only"].get<bool>());
  EXPECT_EQ(people, s["body_frames"].get<int>());  // --jsonl names each scored body's person
  // The same truth one frame late (the figure moves 5 of its 30 pixels a frame) matches fewer bodies.
  write_text(gt, figure_truth(7, 1));
  const RunResult late = run_bodyrec({"eval", "reid-stream", video, "--gt", gt, "--json"});
  ASSERT_EQ(late.exit_code, 0) << late.err;
  EXPECT_LT(last_json_line(late.out)["body_frames"].get<int>(), s["body_frames"].get<int>() - 3);
  // Truth boxes beside every body: a one-line error, not a score of 0.
  write_text(gt, figure_truth(7, 0, 150));
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", video, "--gt", gt}), 3, "overlaps");
}

// The same truth as PETS/CVML XML (0-based frames, boxes by their centre) scores the same.
TEST(ReidStreamGtCli, CvmlTruthScoresAsMotTruthDoes) {
  TempDir dir;
  const std::string video = walking_figure_video(dir / "figure.avi").string(), xml = (dir / "gt.xml").string(),
                    txt = (dir / "gt.txt").string();
  std::string cvml = "<?xml version=\"1.0\"?>\n<dataset>\n";
  for (int f = 0; f < 40; ++f)
    cvml += "<frame number=\"" + std::to_string(f) + "\"><objectlist><object id=\"7\"><box h=\"90\" w=\"30\" xc=\"" +
            std::to_string(35 + 5 * f) + "\" yc=\"145\"/></object></objectlist></frame>\n";
  write_text(xml, cvml + "</dataset>\n");
  write_text(txt, figure_truth(7));
  const RunResult from_xml = run_bodyrec({"eval", "reid-stream", video, "--gt", xml, "--json"});
  const RunResult from_txt = run_bodyrec({"eval", "reid-stream", video, "--gt", txt, "--json"});
  ASSERT_EQ(from_xml.exit_code, 0) << from_xml.err;
  ASSERT_EQ(from_txt.exit_code, 0) << from_txt.err;
  const auto a = last_json_line(from_xml.out), b = last_json_line(from_txt.out);
  EXPECT_EQ(a["identities"].get<int>(), 1);
  EXPECT_EQ(a["body_frames"].get<int>(), b["body_frames"].get<int>());
  EXPECT_DOUBLE_EQ(a["accuracy"].get<double>(), 1.0);
  // An XML file cut in the middle names the file.
  write_text(xml, cvml.substr(0, cvml.size() / 2));
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", video, "--gt", xml}), 3, xml);
}

// An image sequence has no frame times: --fps places them, so the figure walks and is decided as in the video.
TEST(ReidStreamGtCli, AnImageSequenceIsTimedByFps) {
  TempDir dir;
  const std::string frames = walking_figure(dir / "frames").string(), gt = (dir / "gt.txt").string();
  write_text(gt, figure_truth(7));
  const RunResult r = run_bodyrec({"eval", "reid-stream", frames, "--gt", gt, "--fps", "25", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = last_json_line(r.out);
  EXPECT_EQ(s["users"].get<int>(), 1);
  EXPECT_EQ(s["splits"].get<int>(), 0);
  EXPECT_GE(s["body_frames"].get<int>(), 15);
  EXPECT_GE(s["accuracy"].get<double>(), 0.9);  // 0.917: its first frames are still undecided
}

TEST(ReidStreamGtCli, BadGroundTruthAndMisuseAreOneLineErrors) {
  TempDir dir;
  const std::string video = walking_figure_video(dir / "figure.avi").string(), gt = (dir / "gt.txt").string();
  // No truth at all for a video.
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", video, "--json"}), 3, "--gt");
  // Every row ignored (zero confidence).
  write_text(gt, "1,7,20,100,30,90,0,1,1\n");
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", video, "--gt", gt}), 3, "every row is ignored");
  // A broken row names the file and its line.
  write_text(gt, figure_truth(7) + "41,7,abc,100,30,90,1,1,1\n");
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", video, "--gt", gt}), 3, gt);
  // Truth only for frames the video does not have.
  write_text(gt, "500,7,20,100,30,90,1,1,1\n");
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", video, "--gt", gt}), 3, "no ground truth for the frames");
  // A recording has its own truth.
  const auto& rec = synth_recording({"--people", "1", "--seed", "2", "--frames", "20"});
  write_text(gt, figure_truth(7));
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", rec.string(), "--gt", gt}), 2, "--gt");
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", video, "--gt", gt, "--gt-iou", "0"}), 2, "--gt-iou");
}

}  // namespace
}  // namespace bodyrec::testing
