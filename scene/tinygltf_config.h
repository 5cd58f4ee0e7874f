// Include tiny_gltf.h through this header only: one configuration for every translation unit
// (scene/tinygltf_impl.cc explains why).
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>
