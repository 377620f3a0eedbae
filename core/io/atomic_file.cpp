#include "core/io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace pmsim {

namespace {
// A name in the target folder (rename is only atomic within one file system) that no other
// process or thread picks at the same time: pid + a process-wide counter. The extension is kept
// so that writers choosing a format by extension (OpenImageIO) still see it.
std::string temporary_path_for(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path p(path);
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "." + std::string.
  std::string tmp_name(1, '.');
  tmp_name.append(p.stem().string()).append(".tmp").append(std::to_string(::getpid())).append(1, '_');
  tmp_name.append(std::to_string(counter++)).append(p.extension().string());
  return (p.parent_path() / tmp_name).string();
}
}  // namespace

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  if (path.empty()) throw std::runtime_error("cannot write: empty output path");
  const std::string tmp = temporary_path_for(path);
  try {
    write(tmp);
    if (!std::filesystem::exists(tmp)) throw std::runtime_error("the writer produced no file");
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw std::runtime_error(ec.message());
  } catch (const std::exception& e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("cannot write " + path + ": " + e.what());
  }
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw std::runtime_error(std::strerror(errno));
    f << text;
    f.flush();
    if (!f) throw std::runtime_error("write failed (disk full?)");
  });
}

}  // namespace pmsim
