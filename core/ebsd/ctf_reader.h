#pragma once
// Oxford Instruments HKL Channel 5 "Channel Text File" (.ctf), written against the format as the
// Channel 5 software writes it and as MTEX (interfaces/loadEBSD_ctf.m), orix
// (orix/io/plugins/ctf.py) and DREAM3D (ReadCtfData) read it:
//   line 1 "Channel Text File"; then tab-separated "Key<TAB>value" lines (Prj, Author, JobMode,
//   XCells, YCells, XStep, YStep (µm), AcqE1…3, "Euler angles refer to …" with Mag, Coverage,
//   Device, KV, TiltAngle, TiltAxis on the same line); "Phases<TAB>N" followed by N phase lines
//   "a;b;c<TAB>α;β;γ<TAB>Name<TAB>Laue class number<TAB>space group<TAB>…" (Å, degrees); then
//   the column line "Phase X Y Bands Error Euler1 Euler2 Euler3 MAD BC BS" and one line per point,
//   row by row, x fastest. Euler angles are Bunge, in degrees. Phase 0 is a non-indexed point.
// Required: XCells, YCells, XStep, YStep, Phases and the columns Phase, X, Y, Euler1…3; other
// keys and columns are read past. A file holding fewer points than XCells × YCells loads with a
// warning giving both counts, the rest non-indexed; anything malformed is an InputError naming
// the file, the line and the field.
#include <string>

#include "core/ebsd/orientation_map.h"

namespace pmsim {

OrientationMap read_ctf(const std::string& path, const EbsdReadOptions& options = {});

}  // namespace pmsim
