#pragma once
// Writes a whole file or nothing: content goes to a temporary file beside the target, which is then renamed
// over it, so a crash or a full disk never leaves a half-written result that looks complete.
#include <string>
#include <string_view>

namespace imucal::io {

// Throws OutputError naming `path` (and the reason) on any failure; the temporary file is removed.
void writeFileAtomically(const std::string& path, std::string_view content);

}  // namespace imucal::io
