#pragma once
// Bad input is reported with the file, the key and the offending value, so that a user who edited
// a scene by hand can find the line to fix. Command-line tools catch it and exit with code 2.
#include <stdexcept>
#include <string>

namespace pmsim {

struct InputError : std::runtime_error {
  std::string file;    // "" when the value came from the command line (--set)
  std::string key;     // dot path, e.g. "sample.thickness_um"
  std::string value;   // the value as the user wrote it
  std::string reason;  // why it was refused (what() without file, key and value)
  InputError(std::string file_, std::string key_, std::string value_, const std::string& why)
      : std::runtime_error(compose(file_, key_, value_, why)),
        file(std::move(file_)),
        key(std::move(key_)),
        value(std::move(value_)),
        reason(why) {}
  // The same error showing `raw`, the value as the user typed it (validation after parsing only
  // knows the parsed number: 1e+06 for "1000000").
  InputError with_value(std::string raw) const { return InputError(file, key, std::move(raw), reason); }
  // The same error with `prefix` put before the key ("sample.crystal" + "nalpha"): lower modules
  // name keys relative to what they read; the caller knows where that sits in its file.
  InputError under(const std::string& prefix) const {
    return InputError(file, key.empty() ? prefix : prefix + "." + key, value, reason);
  }

 private:
  static std::string compose(const std::string& f, const std::string& k, const std::string& v,
                             const std::string& why) {
    std::string s = f.empty() ? std::string("command line") : f;
    if (!k.empty()) s += ": key '" + k + "'";
    if (!v.empty()) s += " = " + v;
    return s + ": " + why;
  }
};

}  // namespace pmsim
