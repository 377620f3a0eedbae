#pragma once
// EDAX/TSL OIM .ang files, written against the format as OIM writes it (its own header notes,
// quoted in MTEX's interfaces/loadEBSD_ang.m: "Version 3: phi1, PHI, phi2, x, y, iq, ci, phase …
// Version 5: … phase, sem, fit", "Phase index: 0 for single phase, starting at 1 for
// multiphase") and as MTEX, orix (orix/io/plugins/ang.py) and DREAM3D (ReadAngData) read it:
//   header lines start with '#': per phase a block "# Phase k", "# MaterialName", "# Formula",
//   "# Info", "# Symmetry" (the EDAX code, core/ebsd/laue_group.h), "# LatticeConstants a b c α β
//   γ" (Å, degrees), hkl families…; then "# GRID: SqrGrid|HexGrid", "# XSTEP:", "# YSTEP:" (µm),
//   "# NCOLS_ODD:", "# NCOLS_EVEN:", "# NROWS:" and the operator/sample/scan ids.
//   Data lines, blank-separated: φ1 Φ φ2 (Bunge, radians) x y (µm) IQ CI phase [SEM signal, fit,
//   …], row by row, x fastest; on a HexGrid the rows alternate NCOLS_ODD and NCOLS_EVEN points,
//   the even rows shifted by XSTEP/2.
// Non-indexed points: CI = −1 (OIM's mark, which orix follows), Euler angles of 4π (the value OIM
// and orix write for them; MTEX drops such points), or phase 0 in a file of several phases. In a
// single-phase file phase 0 (and 1) is that phase. Files of OIM's versions 1–2 (no phase column,
// 7 columns) are single-phase. Version 1's coordinates scaled by 0.1 are not recognised.
// Required: GRID is optional (SqrGrid when absent), XSTEP, YSTEP, NCOLS_ODD, NCOLS_EVEN, NROWS and
// at least one phase with MaterialName, Symmetry and LatticeConstants. Truncated files load with a
// warning as the .ctf reader's (core/ebsd/point_count.h).
#include <string>

#include "core/ebsd/orientation_map.h"

namespace pmsim {

OrientationMap read_ang(const std::string& path, const EbsdReadOptions& options = {});

}  // namespace pmsim
