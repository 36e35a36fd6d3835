#include "bodyrec/io/roles_csv.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec {
namespace {

using testing::input_error;
using testing::TempDir;
using testing::write_text;

TEST(RolesCsv, ReadsRowsHeaderCommentsAndCrlf) {
  TempDir dir;
  write_text(dir / "r.csv", "\xEF\xBB\xBF" "frame,x,y,w,h,role\r\n# a comment\r\n10,1.5,2,30,60,leader\r\n"
                            "10,40,2,30,60,Member\r\n20,80,5,30,60,non-member\r\n\r\n");
  const auto rows = read_roles_csv((dir / "r.csv").string());
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].frame, 10);
  EXPECT_EQ(rows[0].box, Box(1.5, 2, 30, 60));
  EXPECT_EQ(rows[0].role, Role::kLeader);
  EXPECT_EQ(rows[1].role, Role::kMember);
  EXPECT_EQ(rows[2].frame, 20);
  EXPECT_EQ(rows[2].role, Role::kNonMember);
}

TEST(RolesCsv, BrokenInputNamesFileLineAndField) {
  TempDir dir;
  auto error_for = [&](const std::string& text) {
    write_text(dir / "r.csv", text);
    return input_error([&] { read_roles_csv((dir / "r.csv").string()); });
  };
  EXPECT_EQ(input_error([&] { read_roles_csv((dir / "missing.csv").string()); }),
            (dir / "missing.csv").string() + ": cannot open the roles CSV");
  const std::string f = (dir / "r.csv").string();
  EXPECT_EQ(error_for("1,2,3,4,5\n"), f + ":1: expected 6 fields (frame,x,y,w,h,role), found 5");
  EXPECT_EQ(error_for("frame,x,y,w,h,role\n1,2,abc,4,5,leader\n"), f + ":2: field 'y' is not a number: 'abc'");
  EXPECT_EQ(error_for("-1,2,3,4,5,leader\n"), f + ":1: field 'frame' must be a non-negative integer");
  EXPECT_EQ(error_for("1.5,2,3,4,5,leader\n"), f + ":1: field 'frame' must be a non-negative integer");
  EXPECT_EQ(error_for("1,2,3,0,5,leader\n"), f + ":1: the box needs a positive width and height");
  EXPECT_EQ(error_for("1,2,3,4,5,guide\n"), f + ":1: field 'role' must be leader, member or non-member, not 'guide'");
  EXPECT_EQ(error_for("1,2,3,4,nan,member\n"), f + ":1: field 'h' is not a number: 'nan'");
}

}  // namespace
}  // namespace bodyrec
