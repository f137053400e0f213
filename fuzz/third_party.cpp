// third_party.cpp -- the implementations of the header-only parsers, compiled here with the
// fuzz instrumentation (TLOD_FUZZ only). The normal build links Debian's shared
// libtinygltf.so / libtinyobjloader.so / libstb.so, which libFuzzer could neither steer
// (no coverage) nor check (no ASan); the fuzz build links this file instead, so tinygltf's
// JSON and data-URI handling, stb_image's decoders and tinyobjloader's number parsing are
// fuzzed with the importers that call them. The same headers, with the same (no) macros,
// as tools/import/*.cpp see, so the types agree.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
