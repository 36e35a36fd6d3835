// The gallery as an output of `reid`: an unwritable one is exit 4 like any output, and a run that fails
// before its first frame leaves no gallery file behind (README "Exit codes and errors").
#include <filesystem>

#include <gtest/gtest.h>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

fs::path recording_copy(const TempDir& dir) {
  const fs::path& made = synth_recording({"--frames", "3", "--people", "1", "--seed", "4"});
  fs::copy(made, dir / "rec", fs::copy_options::recursive);
  return dir / "rec";
}

TEST(ReidGallery, AGalleryThatCannotBeCreatedIsAnOutputError) {
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  const std::string gallery = (dir / "no-such-folder" / "g.db").string();
  const RunResult r = run_bodyrec({"reid", rec.string(), "--gallery", gallery, "-q"});
  expect_one_line_error(r, 4, gallery + ": cannot create gallery");
  EXPECT_FALSE(fs::exists(gallery));
}

TEST(ReidGallery, ARunThatFailsOnItsFirstFrameLeavesNoGalleryFile) {
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  write_text(rec / "color" / "000000.png", "not a PNG");
  const fs::path gallery = dir / "g.db";
  const RunResult r = run_bodyrec({"reid", rec.string(), "--gallery", gallery.string(), "-q"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("000000.png"), std::string::npos) << r.err;
  for (const char* suffix : {"", "-wal", "-shm"}) EXPECT_FALSE(fs::exists(gallery.string() + suffix)) << suffix;

  // A gallery that was there before is kept as it was.
  write_text(gallery, "");
  EXPECT_EQ(run_bodyrec({"reid", rec.string(), "--gallery", gallery.string(), "-q"}).exit_code, 3);
  EXPECT_TRUE(fs::exists(gallery));
}

}  // namespace
}  // namespace bodyrec::testing
