#pragma once
// What the fuzz harnesses and the regression test share: one function that feeds bytes to the
// reader of a target, through a file in /dev/shm (the readers take paths).
#include <string>
#include <string_view>
#include <vector>

namespace medax::fuzz {

/// The fuzzed readers, by harness name: off, obj, ply_ascii, ply_binary, stl (read_shape: the
/// mesh reader, or the point-set reader for a file without faces), ma, pipeline, xyz (the
/// point-set reader); the two PLY harnesses share the reader and differ by their seed corpus.
const std::vector<std::string>& targets();

/// Feeds `bytes` to the reader of `target`. Returns true when the input was read, false when
/// the reader refused it with medax's own error (IoError, PipelineError). Anything else (another
/// exception, a sanitizer report, a crash) is a finding.
bool feed(std::string_view target, std::string_view bytes);

}  // namespace medax::fuzz
