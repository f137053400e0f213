# cmake -DIMPORT_C=tools/import/import.c -DFORMATS="gltf;glb;..." -P fuzz/check_importers.cmake
# The ctest test fuzz_covers_importers: fails when tlod_import_file() dispatches a file
# extension (a `_tlod_str_ends_with_nocase(path, ".ext")` in import.c) that has no fuzz target
# in fuzz/CMakeLists.txt (tlod_fuzz_import_formats), i.e. an importer was added unfuzzed.
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
