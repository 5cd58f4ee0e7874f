// The extra images (AOVs) render writes beside each frame, declared once: a name (what `--aov` takes and
// the file's suffix, frame_%06d.<name>.exr), its EXR channels, its unit and what a value means. `--aov`,
// the files and docs/render.md's table follow from this list. Every AOV is a value at the pixel centre
// (the pinhole pass), not a filtered one: a label, not a picture.
#pragma once

#include <string>
#include <vector>

#include "preview/frame_renderer.h"
#include "preview/render_options.h"

namespace cinepath::preview {

struct AovInfo {
  Aov aov;
  const char* name;     // for --aov, and the file's suffix
  const char* channel;  // the EXR channel (one per AOV)
  const char* unit;
  const char* meaning;
};

const std::vector<AovInfo>& AovTable();

// The AOV's values of a rendered frame, one per pixel, row-major.
const std::vector<float>& AovValues(const FrameImage& frame, Aov aov);

// "depth,mask" etc.: names of AovTable in any order, returned in the table's order; InputError naming
// `--aov` for anything else.
std::vector<Aov> ParseAovList(const std::string& text);

}  // namespace cinepath::preview
