#pragma once
// Private to scene: reads the CAD surface kinds of a scene's `surface` map (bspline, step,
// iges, wing) into OCCT-backed geom surfaces, reporting problems at their file:line.

#include <memory>
#include <string>

#include "stitchsim/common/units.h"
#include "stitchsim/geom/surface.h"
#include "stitchsim/scene/yaml_reader.h"

namespace stitchsim::scene::detail {

/// True if `type` is one of the CAD kinds ReadCadSurface reads.
bool IsCadSurfaceType(const std::string& type);

/// The surface of map `s` of kind `type` (IsCadSurfaceType); nullptr when reported.
/// Lengths of a control net are in `unit`; part files carry their own units.
std::unique_ptr<geom::Surface> ReadCadSurface(YamlReader& r, const YAML::Node& s,
                                              const std::string& type, LengthUnit unit,
                                              const FileRefPolicy& files);

}  // namespace stitchsim::scene::detail
