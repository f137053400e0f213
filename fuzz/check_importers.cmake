# cmake -DIMPORT_C=tools/import/import.c -DFORMATS="gltf;glb;..." -P fuzz/check_importers.cmake
# The ctest test fuzz_covers_importers: fails when tlod_import_file() dispatches a file
# extension (a `_tlod_str_ends_with_nocase(path, ".ext")` in import.c) that has no fuzz target
# in fuzz/CMakeLists.txt (tlod_fuzz_import_formats, or tlod_fuzz_vtk_formats: the formats
# fuzz_vtk covers), i.e. an importer was added unfuzzed, or
# when image_decode.h declares a decoder (_tlod_<format>_decode) that fuzz/fuzz_image.c never calls.
cmake_minimum_required(VERSION 3.25)
file(READ "${IMPORT_C}" text)
string(REGEX MATCHALL "_tlod_str_ends_with_nocase\\(path, \"\\.[A-Za-z0-9]+\"\\)" calls "${text}")
set(missing "")
set(seen "")
foreach(call IN LISTS calls)
  string(REGEX REPLACE ".*\"\\.([A-Za-z0-9]+)\".*" "\\1" ext "${call}")
  string(TOLOWER "${ext}" ext)
  list(APPEND seen ${ext})
  if(NOT ext IN_LIST FORMATS)
    list(APPEND missing ${ext})
  endif()
endforeach()
if(NOT seen)
  message(FATAL_ERROR "fuzz_covers_importers: found no extension dispatch in ${IMPORT_C} (did it change shape?)")
endif()
if(missing)
  message(FATAL_ERROR "fuzz_covers_importers: importers without a fuzz target: ${missing} "
                      "(add them to tlod_fuzz_import_formats in fuzz/CMakeLists.txt)")
endif()
message(STATUS "fuzz_covers_importers: every dispatched extension (${seen}) has a fuzz target")

# Image decoders: every _tlod_<format>_decode declared in image_decode.h is called by fuzz_image.c.
file(READ "${IMAGE_H}" image_h)
file(READ "${FUZZ_IMAGE_C}" fuzz_image_c)
string(REGEX MATCHALL "_tlod_[a-z0-9]+_decode\\(" decoders "${image_h}")
list(REMOVE_ITEM decoders "_tlod_image_decode(")
if(NOT decoders)
  message(FATAL_ERROR "fuzz_covers_importers: found no decoder in ${IMAGE_H} (did it change shape?)")
endif()
set(unfuzzed "")
foreach(d IN LISTS decoders)
  string(FIND "${fuzz_image_c}" "${d}" at)
  if(at EQUAL -1)
    list(APPEND unfuzzed ${d})
  endif()
endforeach()
if(unfuzzed)
  message(FATAL_ERROR "fuzz_covers_importers: image decoders fuzz_image.c does not call: ${unfuzzed}")
endif()
message(STATUS "fuzz_covers_importers: every image decoder (${decoders}) is fuzzed by fuzz_image")
