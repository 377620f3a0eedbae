#include "core/ebsd/read_orientation_map.h"

#include "core/base/input_error.h"
#include "core/base/text.h"
#include "core/ebsd/ang_reader.h"
#include "core/ebsd/ctf_reader.h"

namespace pmsim {

namespace {
std::string extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower_case(path.substr(dot));
}
}  // namespace

bool is_orientation_map_path(const std::string& path) {
  const std::string e = extension(path);
  return e == ".ctf" || e == ".ang";
}

OrientationMap read_orientation_map(const std::string& path, const EbsdReadOptions& options) {
  const std::string e = extension(path);
  if (e == ".ctf") return read_ctf(path, options);
  if (e == ".ang") return read_ang(path, options);
  throw InputError(path, "", "", "an EBSD map must be a .ctf (Oxford Channel 5) or .ang (EDAX/TSL) file");
}

}  // namespace pmsim
