// The one tinygltf implementation translation unit of cinepath (the scene reader here, the GLB writer
// in photogrammetry/gltf/gltf_writer.cc).
//
// Debian's libtinygltf is a shared library built without Draco, so cinepath compiles its own. Every
// translation unit that includes tiny_gltf.h must use the same configuration, because the
// TinyGLTF class's default member initializers depend on it: no image codecs (no stb; images stay
// encoded bytes, set by scene/glb_reader.cc's loader callback) and no external image files. Draco is
// not compiled into tinygltf either: scene/glb_reader.cc decodes KHR_draco_mesh_compression itself,
// with bounds checks, and photogrammetry/gltf/gltf_writer.cc encodes it.
#define TINYGLTF_IMPLEMENTATION
#include "scene/tinygltf_config.h"
