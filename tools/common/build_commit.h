#pragma once
// The commit the tools were built from, so that a report says which code it measured.

namespace trs {

/// `git describe --always --dirty` of the source tree at build time, or "unknown".
const char* build_commit();

}  // namespace trs
