#include "bodyrec/report/report.h"

#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/annotate.h"
#include "bodyrec/report/sections.h"
#include "test_support.h"

namespace bodyrec::report {
namespace {

using bodyrec::testing::input_error;

int count(const std::string& text, const std::string& part) {
  int n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

std::vector<std::string> ids(const std::vector<Section>& sections) {
  std::vector<std::string> out;
  for (const auto& s : sections) out.push_back(s.id);
  return out;
}

// 100 frames, tracks 1..3 (track 3 only in frames 40-59); track 1 leads from frame 30 with a direction.
RunData groups_run() {
  RunData run;
  run.name = "run<1>.jsonl";
  run.kind = RunKind::kGroups;
  for (int f = 0; f < 100; ++f) {
    GroupsFrameRow row;
    row.frame = f;
    row.time = f / 7.0;
    row.people.push_back({1, Box(10 + f, 20, 20, 60), f >= 30 ? "leader" : "non-member", f >= 30 ? 0 : -1, "confirmed"});
    row.people.push_back({2, Box(60, 20, 20, 60), f >= 30 ? "member" : "potential-member", f >= 30 ? 0 : -1, "confirmed"});
    if (f >= 40 && f < 60) row.people.push_back({3, Box(100, 30, 20, 60), "non-member", -1, "confirmed"});
    if (f >= 30) {
      GroupsLeader l;
      l.id = 1;
      l.group = 0;
      l.state = "tracking";
      l.box = row.people[0].box;
      l.degrees = 0;
      l.magnitude = 1.5;
      row.leaders.push_back(l);
    }
    row.ms = {{"motion", 0.5}, {"groups", 0.1 + f * 0.01}};
    run.groups.push_back(row);
  }
  return run;
}

RunData reid_run() {
  RunData run;
  run.name = "reid.jsonl";
  run.kind = RunKind::kReid;
  for (int f = 0; f < 30; ++f) {
    ReidFrameRow row;
    row.frame = f;
    row.time = f / 30.0;
    row.bodies.push_back({7, f >= 5 ? std::optional<int>(1) : std::nullopt, "F", Box(0, 0, 10, 20)});
    if (f >= 10) row.bodies.push_back({8, f >= 15 ? std::optional<int>(2) : std::nullopt, "B", Box(20, 0, 10, 20)});
    if (f == 5) row.events.push_back({"enrolled", 1, 7, "F", std::nullopt});
    if (f == 15) row.events.push_back({"recognised", 2, 8, "B", 23.0});
    if (f == 20) row.events.push_back({"view_added", 1, 7, "FR", 0.8});
    row.ms = {{"orient", 1.0}, {"match", 2.0}};
    run.reid.push_back(row);
  }
  return run;
}

// First seen 2026-11-20T13:00:00Z, last seen 13:20:00; scans with pixels in `views_with_scans`.
ReportUser user(int id, const std::string& label, std::initializer_list<int> views_with_scans) {
  ReportUser u;
  u.id = id;
  u.label = label;
  u.first_seen = 1795179600;
  u.last_seen = 1795179600 + 20 * 60;
  for (int v : views_with_scans) {
    u.views[v] = cv::Mat(128, 64, CV_8UC3, cv::Scalar(30 * v, 100, 200));
    u.scanned[v] = true;
  }
  return u;
}

EvalResult eval_of(const std::string& text, const std::string& name = "e.json") { return parse_eval(text, name); }

TEST(ReportSections, GroupsRunGetsGroupSectionsOnly) {
  ReportInput input;
  input.run = groups_run();
  EXPECT_EQ(ids(build_sections(input)),
            (std::vector<std::string>{"header", "roles", "groups", "directions", "key-frames", "speed"}));
}

TEST(ReportSections, ReidRunGetsUsersEventsIdentities) {
  ReportInput input;
  input.run = reid_run();
  EXPECT_EQ(ids(build_sections(input)),
            (std::vector<std::string>{"header", "events", "identities", "key-frames", "speed"}));
  input.have_gallery = true;
  input.evals.push_back(eval_of(R"({"accuracy":0.9,"splits":0,"merges":1,"frames":30,"ms_per_frame":3})"));
  EXPECT_EQ(ids(build_sections(input)),
            (std::vector<std::string>{"header", "users", "events", "identities", "key-frames", "speed", "evaluations"}));
}

// A live run's rows carry arrival, wall and dropped: the report says how many frames were dropped and
// how long decisions took (nearest-rank p50 / p95 of wall - arrival).
TEST(ReportSections, LiveReidRunShowsDroppedFramesAndLatency) {
  ReportInput input;
  input.run = reid_run();
  for (auto& row : input.run.reid) {
    row.arrival = 1795179600.0 + row.frame / 30.0;
    row.wall = *row.arrival + (row.events.empty() ? 0.010 : 0.040 + row.frame / 1000.0);
    row.dropped = row.frame / 10;
    row.ms = {{"detect", 5.0}, {"reid", 2.0}};
  }
  const auto sections = build_sections(input);
  EXPECT_EQ(ids(sections), (std::vector<std::string>{"header", "live", "events", "identities", "key-frames", "speed"}));
  const std::string& html = sections[1].html;
  EXPECT_NE(html.find("30 frames processed, <b>2</b> dropped"), std::string::npos) << html;
  // Events at frames 5, 15, 20: 45, 55, 60 ms; all frames: 27 at 10 ms and those three.
  EXPECT_NE(html.find("<td class=\"num\">3</td><td class=\"num\">55.0 / 60.0</td>"), std::string::npos) << html;
  EXPECT_NE(html.find("<td class=\"num\">30</td><td class=\"num\">10.0 / 55.0</td>"), std::string::npos) << html;
  EXPECT_NE(sections[3].html.find("Bodies from colour alone"), std::string::npos);
  // Not live: no section, and RGB-D bodies say nothing of colour.
  ReportInput recorded;
  recorded.run = reid_run();
  EXPECT_EQ(ids(build_sections(recorded)).at(1), "events");
}

TEST(ReportSections, RoleTimelineHasOneRowPerTrackAndSegmentsPerRoleChange) {
  ReportInput input;
  input.run = groups_run();
  const auto sections = build_sections(input);
  const std::string roles = sections[1].html;
  EXPECT_EQ(count(roles, "class=\"tl-row\""), 3);
  // Track 1: non-member then leader; track 2: potential then member; track 3: one segment.
  EXPECT_EQ(count(roles, "<rect"), 5);
  EXPECT_NE(roles.find("track 1: leader, frames 30–99"), std::string::npos);
  EXPECT_NE(roles.find("track 3: non-member, frames 40–59"), std::string::npos);
  EXPECT_EQ(count(sections[3].html, "class=\"petal\""), 1);  // every leader frame heads right
  EXPECT_NE(sections[3].html.find("70 leader frames"), std::string::npos);
}

TEST(ReportSections, SpeedTableHasMeanAndP95PerStage) {
  ReportInput input;
  input.run = groups_run();
  const std::string speed = build_sections(input).back().html;
  EXPECT_NE(speed.find("<td>motion</td><td class=\"num\">0.50</td><td class=\"num\">0.50</td>"), std::string::npos);
  // groups: 0.10 .. 1.09, mean 0.595, p95 = 95th of 100 sorted values = 0.10 + 0.94.
  EXPECT_NE(speed.find("<td>groups</td><td class=\"num\">0.59</td><td class=\"num\">1.04</td><td class=\"num\">1.09</td>"),
            std::string::npos)
      << speed;
}

TEST(ReportSections, IdentityStripAndEventsOfAReidRun) {
  ReportInput input;
  input.run = reid_run();
  const auto sections = build_sections(input);
  EXPECT_EQ(count(sections[1].html, "class=\"event\""), 3);
  EXPECT_NE(sections[1].html.find("recognised frame 15 track 8 view B score 23.00"), std::string::npos);
  EXPECT_EQ(count(sections[2].html, "class=\"tl-row\""), 2);
  EXPECT_EQ(count(sections[2].html, "<rect"), 4);  // each track: unidentified, then its user
}

TEST(ReportSections, UsersShowEightSlotsWithEmptyOnesVisible) {
  ReportInput input;
  input.run = reid_run();
  input.have_gallery = true;
  input.users = {user(1, "<script>alert(1)</script>", {0, 5}), user(2, "bob", {0, 1, 2, 3, 4, 5, 6, 7}),
                 user(3, "", {})};
  input.users[2].scanned[6] = true;  // a scan stored without its image
  input.users[2].events.push_back({"enrolled", 1795179600 + 90, "BR", std::nullopt, 4, "cam<2>"});
  input.users[2].events.push_back({"recognised", 1795179600 + 600, "BR", 0.8125, 5, ""});
  const std::string page = render_report(input);
  EXPECT_EQ(count(page, "class=\"user\""), 3);
  EXPECT_EQ(count(page, "class=\"view\""), 24);
  EXPECT_EQ(count(page, "<img class=\"scan\""), 10);
  EXPECT_EQ(count(page, "src=\"data:image/jpeg;base64,"), 10);
  EXPECT_EQ(count(page, "class=\"slot empty\">no scan"), 6 + 7);
  EXPECT_EQ(count(page, "class=\"slot withheld\" title=\"BR scan\">no image stored"), 1);
  // Views in reid/view.h order, named under each slot.
  const size_t row2 = page.find("<b style=\"color:" + std::string(palette(2)) + "\">bob</b>");
  ASSERT_NE(row2, std::string::npos);
  std::string captions;
  for (size_t at = page.find("<figcaption>", row2); captions.size() < 40; at = page.find("<figcaption>", at + 1))
    captions += page.substr(at + 12, page.find('<', at + 12) - at - 12) + " ";
  EXPECT_EQ(captions.substr(0, 23), "F FR FL SR SL B BR BL F");
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_NE(page.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(page.find("first seen <time>2026-11-20 13:00:00</time>"), std::string::npos);
  EXPECT_NE(page.find("last seen <time>2026-11-20 13:20:00</time>"), std::string::npos);
  // Users 1 and 2 have events in the run (enrolled, view_added / recognised); user 3 shows the gallery's.
  EXPECT_NE(page.find("2 events in this run"), std::string::npos);
  EXPECT_NE(page.find("1 event in this run"), std::string::npos);
  EXPECT_EQ(count(page, "class=\"uevent\""), 2);
  EXPECT_NE(page.find("recognised BR · 0.81<time>11-20 13:10:00</time>"), std::string::npos);
  EXPECT_NE(page.find("title=\"2026-11-20 13:01:30 UTC, track 4, cam&lt;2&gt;\""), std::string::npos);

  input.images = false;
  const std::string hidden = render_report(input);
  EXPECT_EQ(hidden.find("data:image"), std::string::npos);
  EXPECT_EQ(count(hidden, "class=\"user\""), 3);
  EXPECT_EQ(count(hidden, "image left out"), 11);
  EXPECT_EQ(count(hidden, "class=\"slot empty\">no scan"), 13);
  EXPECT_NE(hidden.find("--no-images"), std::string::npos);
}

TEST(ReportSections, ManyGalleryEventsShowTheMostRecent) {
  ReportInput input;
  input.run = groups_run();
  input.have_gallery = true;
  input.users = {user(4, "", {})};
  for (int i = 0; i < 14; ++i) input.users[0].events.push_back({"recognised", 1795179600.0 + i, "", 0.5, {}, ""});
  const std::string page = render_report(input);
  EXPECT_EQ(count(page, "class=\"uevent\""), 10);
  EXPECT_NE(page.find(">4 earlier…<"), std::string::npos);
  EXPECT_NE(page.find("<time>11-20 13:00:13</time>"), std::string::npos);
  EXPECT_EQ(page.find("<time>11-20 13:00:03</time>"), std::string::npos);
}

TEST(ReportSections, EvaluationsDrawCmcPointsAndPerSceneBars) {
  ReportInput input;
  input.run = groups_run();
  std::string cmc;
  for (int r = 1; r <= 20; ++r) cmc += (r > 1 ? "," : "") + std::to_string(0.4 + r * 0.02);
  input.evals.push_back(eval_of("noise line\n{\"rank1\":0.42,\"rank5\":0.7,\"map\":0.5,\"cmc\":[" + cmc +
                                "],\"matcher\":\"stripes\"}\n"));
  input.evals.push_back(eval_of(R"({"pair_f1":0.8,"pair_precision":0.9,"pair_recall":0.7,"pairs":10,"scene":"hotel"})"));
  input.evals.push_back(eval_of(R"({"pair_f1":0.6,"pair_precision":0.5,"pair_recall":0.7,"pairs":10,"scene":"eth"})"));
  input.evals.push_back(eval_of("{\"mean_px\":3,\"rel_height\":0.05}\n{\"mean_px\":5,\"rel_height\":0.08}\n"
                                "{\"mean_px\":4,\"rel_height\":0.06}\n"));
  const std::string evals = build_sections(input).back().html;
  EXPECT_EQ(count(evals, "class=\"point\""), 20);
  EXPECT_EQ(count(evals, "class=\"bar\""), 2);
  EXPECT_NE(evals.find(">hotel</text>"), std::string::npos);
  EXPECT_EQ(count(evals, "class=\"bin\""), 20);
  EXPECT_NE(evals.find("3 persons, median 0.0600"), std::string::npos);
  EXPECT_EQ(count(evals, "<tr>"), 5);  // header + 4 evaluations
}

TEST(ReportKeyFrames, ChoosesLeaderFramesSpreadOverTheRun) {
  const auto chosen = choose_key_frames(groups_run(), 5);
  ASSERT_EQ(chosen.size(), 5u);
  // Best score: leader + 3 people (frames 40-59); the rest spread at least 10 frames apart, leaders present.
  EXPECT_EQ(chosen[0], 30);
  EXPECT_GE(chosen[1], 40);
  EXPECT_LT(chosen[1], 60);
  for (size_t i = 1; i < chosen.size(); ++i) EXPECT_GE(chosen[i] - chosen[i - 1], 10);
  for (int f : chosen) EXPECT_GE(f, 30);
}

// A re-identification run: the recognition (frame 15) first, then the enrolment (frame 5), 10 frames apart.
TEST(ReportKeyFrames, ReidRunsFavourRecognitionsAndEnrolments) {
  EXPECT_EQ(choose_key_frames(reid_run(), 2), (std::vector<int>{5, 15}));
  RunData run = reid_run();
  ReidFrameRow end;
  end.frame = 30;
  end.end = true;
  end.events.push_back({"left", 1, 7, "F", std::nullopt});
  run.reid.push_back(end);
  for (int f : choose_key_frames(run, 30)) EXPECT_LT(f, 30);  // the closing row is not a frame
}

TEST(ReportKeyFrames, ReidAnnotationColoursBodiesByUser) {
  ReidFrameRow row;
  row.frame = 15;
  row.bodies.push_back({7, 1, "F", Box(50, 100, 40, 80)});
  row.bodies.push_back({8, std::nullopt, "", Box(150, 100, 40, 80)});
  row.events.push_back({"recognised", 1, 7, "F", 23.0});
  RunData run;
  run.kind = RunKind::kReid;
  run.reid.push_back(row);
  cv::Mat image(240, 320, CV_8UC3, cv::Scalar::all(0));
  EXPECT_EQ(annotate_key_frame(image, run, 15), "frame 15 · 2 bodies · user 1 recognised");
  const cv::Scalar user = id_color(1);
  EXPECT_EQ(image.at<cv::Vec3b>(160, 50), cv::Vec3b(static_cast<uchar>(user[0]), static_cast<uchar>(user[1]),
                                                     static_cast<uchar>(user[2])));  // user 1's left edge
  const cv::Vec3b undecided = image.at<cv::Vec3b>(160, 150);  // a thin grey line
  EXPECT_EQ(undecided[0], undecided[1]);
  EXPECT_EQ(undecided[1], undecided[2]);
  EXPECT_GT(undecided[0], 100);
}

TEST(ReportKeyFrames, AnnotationDrawsRoleColoursAndTheArrow) {
  const RunData run = groups_run();
  cv::Mat image(240, 320, CV_8UC3, cv::Scalar::all(0));
  annotate_groups_frame(image, run.groups[50]);
  EXPECT_GT(cv::countNonZero(image.reshape(1)), 500);
  const cv::Vec3b leader = image.at<cv::Vec3b>(40, 60);  // left edge of track 1's box (x = 60)
  EXPECT_EQ(leader, cv::Vec3b(255, 0, 0));
}

TEST(ReportParse, ReadsGroupsAndReidRows) {
  std::istringstream groups(
      R"({"frame":3,"time":0.4,"people":[{"id":4,"box":[1,2,3,4],"role":"leader","group":0,"state":"confirmed"}],)"
      R"("leaders":[{"id":4,"group":0,"state":"tracking","box":[1,2,3,4],"direction":{"degrees":90,"magnitude":2}}],)"
      R"("ms":{"motion":1.5}})"
      "\n\n");
  const RunData g = parse_run(groups, "g.jsonl");
  ASSERT_EQ(g.kind, RunKind::kGroups);
  ASSERT_EQ(g.groups.size(), 1u);
  EXPECT_EQ(g.groups[0].people[0].box, Box(1, 2, 3, 4));
  EXPECT_EQ(*g.groups[0].leaders[0].degrees, 90);
  EXPECT_EQ(g.groups[0].ms, (StageTimes{{"motion", 1.5}}));
  std::istringstream reid(
      R"({"frame":0,"time":0,"bodies":[{"track":2,"user":null,"view":null,"box":[0,0,1,1]}],"events":[]})"
      "\n"
      R"({"frame":1,"time":0.1,"bodies":[{"track":2,"user":5,"view":"SL","box":[0,0,1,1]}],)"
      R"("events":[{"kind":"enrolled","user":5,"track":2,"view":"SL","score":12.5}],"ms":{"match":3}})");
  const RunData r = parse_run(reid, "r.jsonl");
  ASSERT_EQ(r.kind, RunKind::kReid);
  EXPECT_FALSE(r.reid[0].bodies[0].user.has_value());
  EXPECT_EQ(*r.reid[1].bodies[0].user, 5);
  EXPECT_EQ(r.reid[1].events[0].kind, "enrolled");
  EXPECT_EQ(*r.reid[1].events[0].score, 12.5);
  EXPECT_FALSE(r.reid[1].arrival.has_value());
  std::istringstream live(R"({"frame":0,"bodies":[],"arrival":1795179600.25,"wall":1795179600.5,"dropped":3})");
  const RunData l = parse_run(live, "l.jsonl");
  EXPECT_EQ(*l.reid[0].arrival, 1795179600.25);
  EXPECT_EQ(*l.reid[0].wall, 1795179600.5);
  EXPECT_EQ(*l.reid[0].dropped, 3);
  std::istringstream bad(R"({"frame":0,"bodies":[],"dropped":"3"})");
  EXPECT_EQ(input_error([&] { parse_run(bad, "l.jsonl"); }), "l.jsonl:1: field 'dropped' is not an integer");
}

// `bodyrec reid` ends its JSONL with finish()'s events on a line marked "end": true, one frame after the
// last: a closing row, not a frame.
TEST(ReportParse, TheEndRowOfAReidRunIsNotAFrame) {
  std::string text;
  for (int f = 0; f < 3; ++f)
    text += R"({"frame":)" + std::to_string(f) + R"(,"time":)" + std::to_string(f * 0.5) +
            R"(,"bodies":[{"track":1,"user":2,"view":"F","box":[0,0,1,1]}],"events":[]})" + "\n";
  text += R"({"frame":3,"time":1.0,"bodies":[],"events":[{"kind":"left","user":2,"track":1}],"end":true})";
  std::istringstream in(text);
  ReportInput input;
  input.run = parse_run(in, "r.jsonl");
  ASSERT_EQ(input.run.reid.size(), 4u);
  EXPECT_TRUE(input.run.reid[3].end);
  EXPECT_FALSE(input.run.reid[2].end);
  EXPECT_EQ(input.run.frame_count(), 3);
  const std::string header = build_sections(input).front().html;
  EXPECT_NE(header.find("frames <b>3 (0–2, 1.0 s)</b>"), std::string::npos) << header;
  std::istringstream bad(R"({"frame":0,"bodies":[],"end":"yes"})");
  EXPECT_EQ(input_error([&] { parse_run(bad, "r.jsonl"); }), "r.jsonl:1: field 'end' is not true or false");
}

TEST(ReportParse, BrokenRunsNameFileAndLine) {
  auto parse = [](const std::string& text) {
    return input_error([&] {
      std::istringstream in(text);
      parse_run(in, "x.jsonl");
    });
  };
  EXPECT_EQ(parse(""), "x.jsonl: no JSON rows (empty run)");
  EXPECT_EQ(parse("\n  \n"), "x.jsonl: no JSON rows (empty run)");
  EXPECT_EQ(parse("{\"frame\":0,\"people\":[]}\n{\"frame\":1,\"peo").rfind("x.jsonl:2: not JSON", 0), 0u);
  EXPECT_EQ(parse("[1,2]"), "x.jsonl:1: row is not a JSON object");
  EXPECT_EQ(parse("{\"frame\":0}"), "x.jsonl:1: neither 'people' (groups run) nor 'bodies' (re-identification run)");
  EXPECT_EQ(parse("{\"people\":[]}"), "x.jsonl:1: missing field 'frame'");
  EXPECT_EQ(parse("{\"frame\":4,\"people\":[{\"box\":[0,115,35,240],\"height_m\":1.6,\"pixels\":3360}]}"),
            "x.jsonl:1: a person without 'id': not a groups run (report reads the --jsonl of groups or reid, not of "
            "segment or landmark)");
  EXPECT_EQ(parse("{\"frame\":0,\"people\":[{\"id\":1,\"box\":[1,2]}]}"), "x.jsonl:1: field 'box' is not [x, y, w, h]");
  EXPECT_EQ(parse("{\"frame\":0,\"people\":[]}\n{\"frame\":1,\"bodies\":[]}"),
            "x.jsonl:2: a re-identification row in a groups run");
  EXPECT_EQ(parse("{\"frame\":0,\"bodies\":[{\"track\":\"a\"}]}"), "x.jsonl:1: field 'track' is not an integer");
  EXPECT_EQ(parse("{\"frame\":0,\"people\":[],\"ms\":{\"motion\":\"slow\"}}"),
            "x.jsonl:1: field 'ms.motion' is not a number");
}

TEST(ReportParse, EvalKindsFromKeysAndBrokenEvals) {
  EXPECT_EQ(eval_of(R"({"rank1":0.4,"cmc":[0.4,0.6]})").cmc.size(), 2u);
  EXPECT_EQ(eval_of(R"({"accuracy":0.9,"splits":0,"merges":0})").kind, EvalKind::kReidStream);
  EXPECT_EQ(eval_of(R"({"pair_f1":0.9})").kind, EvalKind::kGroups);
  EXPECT_EQ(eval_of(R"({"mean_px":2,"mean_rel_height":0.1})").kind, EvalKind::kLandmarks);
  EXPECT_EQ(eval_of(R"({"mota":0.7})").kind, EvalKind::kTrack);
  EXPECT_EQ(eval_of(R"({"ap50":0.7})").kind, EvalKind::kDetect);
  EXPECT_EQ(eval_of(R"({"accuracy":0.7,"confusion":[]})").kind, EvalKind::kRoles);
  EXPECT_EQ(eval_of(R"({"mean_iou":0.7})").kind, EvalKind::kSegment);
  EXPECT_EQ(input_error([] { parse_eval("", "e.json"); }), "e.json: empty evaluation file");
  EXPECT_EQ(input_error([] { parse_eval("{\"x\":1}\nscore 3\n", "e.json"); }),
            "e.json:2: the last line is not the JSON object of an eval command run with --json");
  EXPECT_EQ(input_error([] { parse_eval("{\"x\":1}", "e.json"); }).rfind("e.json:1: unknown evaluation", 0), 0u);
  EXPECT_EQ(input_error([] { parse_eval("{\"rank1\":1,\"cmc\":[\"a\"]}", "e.json"); }),
            "e.json:1: field 'cmc' holds a non-number");
  EXPECT_EQ(input_error([] { parse_eval("{\"mean_px\":1,\"rel_height\":0.1}\n{\"mean_px\":1,\"rel_height\":\"x\"}",
                                        "e.json"); }),
            "e.json:2: field 'rel_height' is not a number");
}

TEST(ReportPage, IsSelfContainedAndEscapesTheRunName) {
  ReportInput input;
  input.run = groups_run();
  input.generated = "2026-11-23 15:00 UTC";
  const std::string page = render_report(input);
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(page.find("<script"), std::string::npos);
  EXPECT_EQ(count(page, "http://"), count(page, "http://www.w3.org/2000/svg"));  // only the SVG namespace
  EXPECT_EQ(page.find("https://"), std::string::npos);
  EXPECT_NE(page.find("run&lt;1&gt;.jsonl"), std::string::npos);
  EXPECT_NE(page.find("embeds images of people"), std::string::npos);
  EXPECT_NE(page.find("Give --source VIDEO"), std::string::npos);
  EXPECT_EQ(count(page, "<section "), 5);
}

}  // namespace
}  // namespace bodyrec::report
