#pragma once
// The symmetry codes the two vendors write for a phase, as Laue class and crystal system.
//   Oxford Channel 5 (.ctf phase line, 4th field): the Laue class number 1…11 =
//     -1, 2/m, mmm, 4/m, 4/mmm, -3, -3m, 6/m, 6/mmm, m-3, m-3m
//     (the order MTEX's loadEBSD_ctf and orix's ctf reader use for Channel 5 files).
//   EDAX/TSL (.ang "# Symmetry"): the rotation group written as digits = 1 (-1), 2, 20, 21
//     (2/m, unique axis c, b, a), 22 (mmm), 4 (4/m), 42 (4/mmm), 3 (-3), 32 (-3m), 6 (6/m),
//     62 (6/mmm), 23 (m-3), 43 (m-3m) (the codes of EDAX OIM as MTEX's loadEBSD_ang and
//     DREAM3D's EbsdLib read them).
#include <optional>
#include <string>
#include <string_view>

#include "core/crystal/lattice.h"

namespace pmsim {

struct LaueClass {
  std::string symbol;  // Hermann–Mauguin ("6/mmm")
  CrystalSystem system = CrystalSystem::Triclinic;
};

std::optional<LaueClass> laue_class_from_ctf(long number);
std::optional<LaueClass> laue_class_from_ang(std::string_view code);

}  // namespace pmsim
