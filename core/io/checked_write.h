#pragma once
// Writing a file's bytes so that no failure is silent: a short write, a full disk (ENOSPC), a
// file-size limit (EFBIG) and a failing fsync or close are all errors. Encoders that report
// success on a failed fwrite (OpenImageIO's PNG writer did: reliability finding F9) encode into
// memory and leave the file write to this.
#include <string>
#include <vector>

namespace pmsim {

// Creates or truncates `path`, writes `bytes`, fsyncs and closes; throws std::runtime_error with
// strerror's text on any failure.
void write_bytes_checked(const std::string& path, const std::vector<unsigned char>& bytes);

}  // namespace pmsim
