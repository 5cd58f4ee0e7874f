// The files the previs page is made of, compiled into the binary (viewer/EmbedAssets.cmake), so that
// `cinepath view` writes the same page from any folder and from an installed binary.
#pragma once

#include <string_view>

namespace cinepath::viewer {

std::string_view PrevisHtml();       // viewer/previs.html: the page template with @NAME@ placeholders
std::string_view PrevisJs();         // viewer/previs.js: the page's code (an ES module)
std::string_view ThreeModuleJs();    // third_party/three/three.module.min.js
std::string_view OrbitControlsJs();  // third_party/three/OrbitControls.js (imports 'three')

}  // namespace cinepath::viewer
