// The one tinygltf implementation translation unit of cinepath_photogrammetry.
//
// stack.md: Debian's libtinygltf is a shared library built without Draco. cinepath writes Draco
// itself (gltf_writer.cc encodes with the Draco library and adds KHR_draco_mesh_compression), so
// this TU compiles tinygltf's writer/reader without images (no stb) and without Draco.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
