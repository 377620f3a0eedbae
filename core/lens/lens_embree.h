#pragma once
// A lens as a primitive of an Embree 3 scene (paper §5: "lens is … a primitive of a 3D scene"):
// a user geometry with one primitive whose bounds/intersect/occluded callbacks use LensGeometry in
// double precision, so many lenses and ordinary triangle meshes are traced through one RTCScene.
//
// Hit record for a lens: geomID = the returned id, primID = 0, Ng = outward unit normal of the
// surface hit, u = surface index (0 front cap, 1 back cap, 2 ledge), v = 0, tfar = distance in
// units of the ray's dir (Embree rays need not be unit). Ray filter functions are not invoked.
// A ray continuing from a point on a lens (an SML outgoing ray) should start with tnear of about
// 1e-6·lens size to skip its own surface, as for any Embree geometry.
#include <embree3/rtcore.h>

#include "core/lens/lens.h"

namespace pmsim {

// Creates, commits and attaches the user geometry; returns its geometry ID. `lens` is referenced,
// not copied: it must outlive the scene (and must not move). Commit the scene afterwards.
unsigned attach_lens(RTCDevice device, RTCScene scene, const LensGeometry& lens);

// The surface a lens hit record refers to (from RTCHit::u).
inline LensSurface lens_surface_from_hit_u(float u) {
  return u < 0.5f ? LensSurface::Front : (u < 1.5f ? LensSurface::Back : LensSurface::Ledge);
}

}  // namespace pmsim
