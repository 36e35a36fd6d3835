#include "bodyrec/core/model_files.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {
namespace fs = std::filesystem;

class ModelFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("bodyrec_models_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "tiny.dat") << "x";
    setenv("BODYREC_MODELS", dir_.c_str(), 1);
  }
  void TearDown() override {
    unsetenv("BODYREC_MODELS");
    fs::remove_all(dir_);
  }
  fs::path dir_;
};

TEST_F(ModelFiles, TheEnvironmentDirectoryComesFirst) {
  const auto dirs = model_directories();
  ASSERT_FALSE(dirs.empty());
  EXPECT_EQ(dirs.front(), fs::weakly_canonical(dir_).string());
  const auto found = find_model_file("tiny.dat");
  ASSERT_TRUE(found);
  EXPECT_EQ(*found, (fs::weakly_canonical(dir_) / "tiny.dat").string());
}

TEST_F(ModelFiles, AMissingModelNamesItselfAndTheHint) {
  EXPECT_FALSE(find_model_file("no-such-model.dat"));
  try {
    require_model_file("no-such-model.dat", "train one with bodyrec train-x");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no-such-model.dat"), std::string::npos) << what;
    EXPECT_NE(what.find(fs::weakly_canonical(dir_).string()), std::string::npos) << what;
    EXPECT_NE(what.find("train one with bodyrec train-x"), std::string::npos) << what;
  }
}

TEST_F(ModelFiles, ADirectoryNamedAsAFileIsNotAModel) {
  fs::create_directories(dir_ / "dir.dat");
  EXPECT_FALSE(find_model_file("dir.dat"));
}

}  // namespace
}  // namespace bodyrec
