#pragma once
// render.native=on: an EBSD map rendered with one pixel per map point, for direct comparison with
// a photomicrograph (or the vendor's map) of the same area (issue 13).
//
// The image is the map's columns wide and its rows tall (on a grid with step_y ≠ step_x, e.g. a
// hexagonal one, rows·step_y/step_x rounded: pixels stay square, one per point along x), and the
// field is framed to it: the eyepiece's field number becomes step_x · min(width, height) ·
// magnification, so that mm_per_pixel (view_geometry.h) is the step and, at the default stage
// (0, 0), pixel centres fall on the points. Stage translation and rotation apply as always.
// Scenes without a map on the stage are returned unchanged.
#include "core/microscope/scene.h"

namespace pmsim {

Scene native_resolution_scene(const Scene& scene);

}  // namespace pmsim
