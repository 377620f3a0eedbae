#pragma once
// `--script FILE`: a list of user actions replayed through the same paths as the mouse and the
// keyboard (injected into ImGui's input state, then handled by the widgets and the shortcut
// table). One command per line; `#` starts a comment; coordinates are window pixels (0,0 top left).
//
//   set KEY=VALUE          change a scene key (as --set; same commit as a widget)
//   key CHORD              press a shortcut: key Left | key shift+Right | key ctrl+s | key C
//   move X Y               move the mouse (hovering the field probes that point)
//   click X Y              left click
//   drag X0 Y0 X1 Y1 [N]   press at (X0,Y0), move to (X1,Y1) over N frames (default 10), release
//   turn-stage DEG [N]     drag on the field along an arc about its centre sweeping DEG degrees
//   pan DX DY [N]          right-button drag from the field centre by (DX, DY) field widths: translates the stage
//                          (counter-clockwise positive), over N frames (default 12)
//   probe FX FY            hover the field at fractions (0..1 from its top left)
//   type TEXT              type text into the focused text field
//   wait N                 run N frames
//   wait converged [S]     run frames until the image has converged (give up after S s, def. 600)
//   screenshot FILE.png    the whole window as the user sees it
//   export FILE            the field image (.png sRGB, .exr/.tif linear), scene in the metadata
//   save FILE / load FILE  scene files
//   expect-error           the previous command must have raised the error banner
//   exercise open FILE     open a student's <name>.pmexercise.json (its specimen and Exercise tab)
//   exercise answer TASK VALUE   type VALUE (the rest of the line; none: clear) as TASK's answer
//   exercise check         Check (grade at once, when the exercise allows); waits for the grades
//   exercise reveal on|off the reveal layer (after check); `on` waits until it shows the scene
//   exercise save          write <name>.answers.json beside the exercise file (atomically)
//   exercise goto TASK     put TASK's grain under the crosshair
//   exercise wait          frames until the Check and the reveal layer are done
//   identify KEY VALUE     an observation in the Identify tab, as pmsim-exercise identify --KEY VALUE
//                          (VALUE: the rest of the line; none clears KEY); brings the tab to the front
//   identify clear         every observation cleared
//
// A command that raises the error banner stops the script (exit 2) unless the next line is
// `expect-error`; the scene stays the last good one either way.
#include <string>
#include <vector>

#include "ui/ui_driver.h"

namespace pmsim::ui {

struct ScriptCommand {
  std::string verb;
  std::vector<std::string> args;
  int line = 0;
};

// Throws InputError(file, "line N", text, why) on an unknown verb or wrong arguments.
std::vector<ScriptCommand> parse_script(const std::string& text, const std::string& file);
std::vector<ScriptCommand> load_script(const std::string& path);

struct ScriptResult {
  bool ok = true;
  std::string error;  // what stopped the script (file, line, message)
  int frames = 0;
};

// Runs the commands on `driver`; `file` names the script in messages.
ScriptResult run_script(UiDriver& driver, const std::vector<ScriptCommand>& commands,
                        const std::string& file);

// Frames until the renderer has converged and the converged image is on screen; false on timeout.
bool settle(UiDriver& driver, double timeout_s, int* frames = nullptr);

}  // namespace pmsim::ui
