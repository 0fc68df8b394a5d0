// Writes a file so that it appears whole or not at all: the content goes to a temporary file
// beside the target, which replaces the target only once everything was written and flushed.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace syncap::io {

// Calls write_content with a binary stream to a temporary file in path's folder, then renames it
// to path. Throws ExportError naming path when the folder is not writable or a write fails; when
// it throws, and when write_content throws (rethrown as is), the temporary file is removed and an
// existing file at path is left untouched.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write_content);

}  // namespace syncap::io
