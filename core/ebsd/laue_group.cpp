#include "core/ebsd/laue_group.h"

namespace pmsim {

std::optional<LaueClass> laue_class_from_ctf(long n) {
  using S = CrystalSystem;
  switch (n) {
    case 1: return LaueClass{"-1", S::Triclinic};
    case 2: return LaueClass{"2/m", S::Monoclinic};
    case 3: return LaueClass{"mmm", S::Orthorhombic};
    case 4: return LaueClass{"4/m", S::Tetragonal};
    case 5: return LaueClass{"4/mmm", S::Tetragonal};
    case 6: return LaueClass{"-3", S::Trigonal};
    case 7: return LaueClass{"-3m", S::Trigonal};
    case 8: return LaueClass{"6/m", S::Hexagonal};
    case 9: return LaueClass{"6/mmm", S::Hexagonal};
    case 10: return LaueClass{"m-3", S::Cubic};
    case 11: return LaueClass{"m-3m", S::Cubic};
    default: return std::nullopt;
  }
}

std::optional<LaueClass> laue_class_from_ang(std::string_view c) {
  using S = CrystalSystem;
  if (c == "1") return LaueClass{"-1", S::Triclinic};
  if (c == "2" || c == "20" || c == "21") return LaueClass{"2/m", S::Monoclinic};
  if (c == "22") return LaueClass{"mmm", S::Orthorhombic};
  if (c == "4") return LaueClass{"4/m", S::Tetragonal};
  if (c == "42") return LaueClass{"4/mmm", S::Tetragonal};
  if (c == "3") return LaueClass{"-3", S::Trigonal};
  if (c == "32") return LaueClass{"-3m", S::Trigonal};
  if (c == "6") return LaueClass{"6/m", S::Hexagonal};
  if (c == "62") return LaueClass{"6/mmm", S::Hexagonal};
  if (c == "23") return LaueClass{"m-3", S::Cubic};
  if (c == "43") return LaueClass{"m-3m", S::Cubic};
  return std::nullopt;
}

}  // namespace pmsim
