# cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<dir> -DC_COMPILER=cc -DCXX_COMPILER=c++ -P tests/headers/check_headers.cmake
# Behind the ctest test `public_headers` (tests/headers/CMakeLists.txt) and the `headers` stage of
# .ci/run. Every public header, <module>/include/tesslod/*.h and <dir>/<module>/include/tesslod/*.h
# (globbed when the check runs, so a header added later is covered without reconfiguring), is
# compiled ALONE from a generated source (`#include <tesslod/NAME.h>` twice, so the include
# guard is exercised, and one typedef: a header of macros alone would leave ISO C's forbidden
# empty translation unit) as
#   C99 and C11:  -std=c99 / -std=c11 -pedantic -Wall -Wextra -Werror
#   C++11:        -std=c++11 -pedantic -Wall -Wextra -Werror
# with only the modules' include directories on the path: each header must be self-contained,
# strict-standard and usable from C++. All failures are listed, then the check fails.
cmake_minimum_required(VERSION 3.25)
foreach(var SOURCE_DIR WORK_DIR C_COMPILER CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "check_headers.cmake: -D${var}=... is required")
  endif()
endforeach()

file(GLOB headers LIST_DIRECTORIES false
  "${SOURCE_DIR}/*/include/tesslod/*.h" "${SOURCE_DIR}/*/*/include/tesslod/*.h")
list(FILTER headers EXCLUDE REGEX "^${SOURCE_DIR}/build/") # build trees hold installed copies
list(SORT headers)
if(NOT headers)
  message(FATAL_ERROR "check_headers.cmake: no public headers under ${SOURCE_DIR}/*/include/tesslod")
endif()
set(include_args "")
foreach(h IN LISTS headers)
  get_filename_component(dir "${h}" DIRECTORY) # .../include/tesslod
  get_filename_component(dir "${dir}" DIRECTORY) # .../include
  list(APPEND include_args "-I${dir}")
endforeach()
list(REMOVE_DUPLICATES include_args)

set(modes "c99|c|${C_COMPILER}|-std=c99" "c11|c|${C_COMPILER}|-std=c11" "cxx11|cpp|${CXX_COMPILER}|-std=c++11")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(failed "")
set(passed 0)
foreach(h IN LISTS headers)
  get_filename_component(name "${h}" NAME_WE)
  foreach(mode IN LISTS modes)
    string(REPLACE "|" ";" m "${mode}")
    list(GET m 0 tag)
    list(GET m 1 ext)
    list(GET m 2 compiler)
    list(GET m 3 std)
    set(src "${WORK_DIR}/${name}_${tag}.${ext}")
    file(WRITE "${src}" "#include <tesslod/${name}.h>\n#include <tesslod/${name}.h>\ntypedef int tlod_header_check_${tag};\n")
    execute_process(
      COMMAND "${compiler}" ${std} -pedantic -Wall -Wextra -Werror ${include_args} -fsyntax-only "${src}"
      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
    file(RELATIVE_PATH rel "${SOURCE_DIR}" "${h}")
    if(rc EQUAL 0)
      math(EXPR passed "${passed} + 1")
    else()
      list(APPEND failed "${rel} (${std})")
      message("--- ${rel} as ${std} -pedantic -Wall -Wextra -Werror:\n${out}")
    endif()
  endforeach()
endforeach()

list(LENGTH headers nh)
if(failed)
  list(LENGTH failed nf)
  list(JOIN failed "\n  " text)
  message(FATAL_ERROR "public headers: ${nf} of ${passed}+${nf} compilations failed:\n  ${text}")
endif()
message(STATUS "public headers: ${nh} headers x (C99, C11, C++11) = ${passed} compilations OK")
