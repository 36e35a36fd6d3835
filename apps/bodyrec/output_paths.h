// Outputs never overwrite the run's own inputs or each other: `detect video.avi --jsonl video.avi` or
// `reid REC --gallery g.db --jsonl g.db` would otherwise destroy the video or the gallery before the first
// frame is read, and `--jsonl X --mot X` would interleave two formats in one file.
#pragma once

#include <CLI/CLI.hpp>

namespace bodyrec::cli {

// The options that name files or folders a command writes (some commands also write their --gallery,
// which the check treats as an input that must not be overwritten by another output).
bool is_output_option(const CLI::Option& option);

// Throws UsageError when a given output option names the same file or folder as any other given option
// of `command` ("--jsonl v.avi is also source: give another path"). "-" (stdout) and existing paths that
// are neither files nor folders (/dev/null, /dev/stdout) are never a clash.
void check_output_paths(const CLI::App& command);

// Runs check_output_paths for `app` and every subcommand at any depth, once its options are parsed and
// before it runs. Call it once the whole command tree is built, before parsing.
void check_output_paths_everywhere(CLI::App& app);

}  // namespace bodyrec::cli
