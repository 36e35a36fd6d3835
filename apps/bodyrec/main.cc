// bodyrec: people recognition from body shape and appearance with one camera or RGB-D sensor.
// This file only wires the registered subcommands together and maps errors to exit codes.
#include <cstdlib>
#include <iostream>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/core/openblas.h"
#include "command.h"
#include "option_checks.h"
#include "option_error_text.h"
#include "output_paths.h"

namespace {

// OpenCV and FFmpeg print their own multi-line diagnostics (GStreamer probing, damaged blocks); bodyrec
// reports each failure as one line instead. Setting OPENCV_LOG_LEVEL or OPENCV_FFMPEG_LOGLEVEL in the
// environment brings them back for debugging.
void quiet_library_logs() {
  if (!std::getenv("OPENCV_LOG_LEVEL")) cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  setenv("OPENCV_FFMPEG_LOGLEVEL", "-8", 0);  // AV_LOG_QUIET
}

}  // namespace

int main(int argc, char** argv) {
  quiet_library_logs();
  bodyrec::choose_openblas_core();  // before any BLAS call: OpenBLAS 0.3.21 misjudges newer CPUs
  CLI::App app{
      "bodyrec: finds people, outlines their body contours, tells group leaders from members and\n"
      "passers-by, and re-identifies people who come back, with one camera or one RGB-D sensor.\n"
      "Exit codes: 0 ok, 2 usage error, 3 input error, 4 processing error.",
      "bodyrec"};
  app.option_defaults()->always_capture_default();
  app.set_version_flag("--version", std::string(BODYREC_VERSION));
  app.require_subcommand(1);
  app.fallthrough();

  CLI::App* eval = app.add_subcommand("eval", "Score a stage against ground truth");
  eval->require_subcommand(1);
  for (const auto& command : bodyrec::cli::registered_commands()) {
    command.add(command.parent == "eval" ? *eval : app);
  }
  bodyrec::cli::check_numbers_everywhere(app);  // NaN, infinities and non-numbers: usage errors everywhere
  bodyrec::cli::hide_empty_list_defaults_everywhere(app);
  bodyrec::cli::check_output_paths_everywhere(app);  // no output overwrites an input or another output

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::cerr << "bodyrec: error: " << bodyrec::cli::usage_message(e, app) << "\n";
    return static_cast<int>(bodyrec::ExitCode::kUsage);
  } catch (const bodyrec::OptionError& e) {
    std::cerr << "bodyrec: error: " << bodyrec::cli::option_error_text(e, app) << "\n";
    return static_cast<int>(e.code());
  } catch (const bodyrec::Error& e) {
    std::cerr << "bodyrec: error: " << bodyrec::cli::one_line(e.what()) << "\n";
    return static_cast<int>(e.code());
  } catch (const cv::Exception& e) {
    std::cerr << "bodyrec: error: OpenCV: " << bodyrec::cli::one_line(e.err) << " (in " << e.func << ")\n";
    return static_cast<int>(bodyrec::ExitCode::kProcessing);
  } catch (const std::exception& e) {
    std::cerr << "bodyrec: error: " << bodyrec::cli::one_line(e.what()) << "\n";
    return static_cast<int>(bodyrec::ExitCode::kProcessing);
  }
  return 0;
}
