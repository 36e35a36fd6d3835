#include "bodyrec/io/frame_folder.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::TempDir;
using bodyrec::testing::write_text;

TEST(FrameFolder, CountsTheFramesOfAnEarlierRunThatThisOneDidNotReplace) {
  TempDir dir;
  const std::filesystem::path out = dir / "frames";
  {
    FrameFolder first(out.string());
    EXPECT_EQ(first.stale(), 0u);
    for (int f = 0; f < 5; ++f) write_text(first.file(f), "x");
    write_text(first.file(2, "_body0"), "x");
    EXPECT_EQ(first.stale_note(), "");
  }
  write_text(out / "notes.txt", "mine");  // not a frame file: never counted
  write_text(out / "12345.png", "x");     // 5 digits: not a frame file
  FrameFolder second(out.string());
  EXPECT_EQ(second.file(0), (out / "000000.png").string());
  second.file(1);
  EXPECT_EQ(second.stale(), 4u);  // 000002-000004 and 000002_body0
  EXPECT_EQ(second.stale_note(), out.string() + " holds 4 frame files of an earlier run that this run did not "
                                                "replace (000002.png ... 000004.png)");
  EXPECT_TRUE(std::filesystem::exists(out / "000004.png"));  // nothing deleted
}

TEST(FrameFolder, FrameFileNames) {
  EXPECT_TRUE(is_frame_file_name("000123.png"));
  EXPECT_TRUE(is_frame_file_name("000123_body2.png"));
  EXPECT_FALSE(is_frame_file_name("00012.png"));
  EXPECT_FALSE(is_frame_file_name("000123.jpg"));
  EXPECT_FALSE(is_frame_file_name("a00123.png"));
}

TEST(FrameFolder, AFolderThatCannotBeCreatedIsAProcessingError) {
  TempDir dir;
  write_text(dir / "file", "x");
  EXPECT_THROW(FrameFolder((dir / "file" / "sub").string()), ProcessingError);
}

}  // namespace
}  // namespace bodyrec
