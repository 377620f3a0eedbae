#pragma once
// Scene files (JSON) and `--set key=value` overrides. The keys are the dot paths documented in
// core/microscope/scene.h; they are a contract that scripts and saved scenes rely on.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/microscope/scene.h"

namespace pmsim {

// Parses a scene; throws InputError naming file, key and value on a bad value, a wrong type or a
// missing file. Unknown keys are not errors: each is appended to `warnings` as a message that
// names the key (the command-line tools print them on stderr).
Scene scene_from_json(const nlohmann::json& j, const std::string& file,
                      std::vector<std::string>* warnings = nullptr);
Scene load_scene_file(const std::string& path, std::vector<std::string>* warnings = nullptr);
// The text of a scene file (any type); InputError naming the file when it cannot be read.
std::string read_scene_text(const std::string& path);

// The full state, every key, so that save → load round-trips exactly.
nlohmann::json scene_to_json(const Scene& scene);
// Atomic: writes a temporary file in the same folder and renames it into place.
void save_scene_file(const Scene& scene, const std::string& path);

// One `--set key=value`: value is parsed as JSON when it parses (numbers, [x,y,z], objects),
// else taken as a string. Throws InputError(file "", key, value) on an unknown key or bad value,
// leaving the scene unchanged; the scene is validated after the setting applies.
void apply_setting(Scene& scene, std::string_view key, std::string_view value);
// "key=value" form.
void apply_setting(Scene& scene, std::string_view assignment);
// Every "key=value" of a command line, in order, then one validation of the result: settings
// valid only together (sample.x_axis and sample.z_axis turned at once) are accepted in any
// order. On an error the scene is unchanged.
void apply_settings(Scene& scene, const std::vector<std::string>& assignments);

// Range and consistency checks shared by every input path (file, --set, UI); throws InputError.
void validate_scene(const Scene& scene, const std::string& file = "");

}  // namespace pmsim
