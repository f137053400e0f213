# cmake -P script behind the ctest test `install_consumer` (see CMakeLists.txt for the -D inputs).
#   1. cmake --install <build dir> --prefix <prefix>        (prefix wiped first; it lives in the build dir)
#   2. checks the installed layout and that the export leaks no build/source paths
#   3. find_package(tesslod CONFIG) consumer: configure + build in <prefix>/consumer-build, run it
#   4. pkg-config consumer: cc consumer.c $(pkg-config --cflags --libs tesslod), run it
# With TLOD_BACKEND_GL, both consumers also build consumer_gl.c (TLOD_CONSUMER_GL=1): the installed
# "gl" backend draws in an EGL context the consumer makes (the pkg-config one adds `egl` for that;
# the GL library itself must come from tesslod.pc / the CMake package).
# CONSUMER_FLAGS (e.g. -fsanitize=address,undefined) go on both consumers' compile and link lines.
cmake_minimum_required(VERSION 3.25)

foreach(var TLOD_BINARY_DIR TLOD_SOURCE_DIR TLOD_VERSION TLOD_PREFIX TLOD_LIBDIR TLOD_INCLUDEDIR
            CONSUMER_SOURCE_DIR CONSUMER_C_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "install_consumer.cmake: -D${var}=... is required")
  endif()
endforeach()
separate_arguments(consumer_flags UNIX_COMMAND "${CONSUMER_FLAGS}")

function(run what)
  string(REPLACE ";" " " shown "${ARGN}")
  message(STATUS "[install_consumer] ${what}: ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "[install_consumer] FAILED (${rc}): ${what}")
  endif()
endfunction()

function(expect_exists path)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "[install_consumer] missing from the install: ${path}")
  endif()
endfunction()

# The prefix is <build>/tests/install/prefix: unique per build dir, and safe to wipe.
cmake_path(IS_PREFIX TLOD_BINARY_DIR "${TLOD_PREFIX}" NORMALIZE prefix_in_build)
if(NOT prefix_in_build)
  message(FATAL_ERROR "[install_consumer] refusing to wipe ${TLOD_PREFIX}: not inside ${TLOD_BINARY_DIR}")
endif()
file(REMOVE_RECURSE "${TLOD_PREFIX}")

set(config_args "")
if(TLOD_CONFIG)
  set(config_args --config "${TLOD_CONFIG}")
endif()

# --- 1. install -------------------------------------------------------------------------------
run("install" "${CMAKE_COMMAND}" --install "${TLOD_BINARY_DIR}" --prefix "${TLOD_PREFIX}" ${config_args})

# --- 2. layout --------------------------------------------------------------------------------
set(inc "${TLOD_PREFIX}/${TLOD_INCLUDEDIR}")
set(lib "${TLOD_PREFIX}/${TLOD_LIBDIR}")
set(expect_headers core.h lod.h cpu.h backend.h)
set(expect_libs core lod cpu backend)
if(TLOD_BACKEND_GL)
  list(APPEND expect_headers gl.h)
  list(APPEND expect_libs gl)
endif()
foreach(h IN LISTS expect_headers)
  expect_exists("${inc}/tesslod/${h}")
endforeach()
foreach(l IN LISTS expect_libs)
  expect_exists("${lib}/libtesslod_${l}.a")
endforeach()
foreach(f tesslodConfig.cmake tesslodConfigVersion.cmake tesslodTargets.cmake)
  expect_exists("${lib}/cmake/tesslod/${f}")
endforeach()
expect_exists("${lib}/pkgconfig/tesslod.pc")

file(GLOB_RECURSE installed_headers RELATIVE "${TLOD_PREFIX}" "${TLOD_PREFIX}/*.h")
foreach(h IN LISTS installed_headers)
  if(NOT h MATCHES "^${TLOD_INCLUDEDIR}/tesslod/[^/]+\\.h$" OR h MATCHES "internal")
    message(FATAL_ERROR "[install_consumer] unexpected header installed: ${h} (only public tesslod/*.h belong there)")
  endif()
endforeach()

file(GLOB targets_files "${lib}/cmake/tesslod/tesslodTargets*.cmake")
foreach(f IN LISTS targets_files)
  file(READ "${f}" text)
  foreach(leak "${TLOD_SOURCE_DIR}/" "${TLOD_BINARY_DIR}/" "tlod_build_flags")
    string(FIND "${text}" "${leak}" pos)
    if(NOT pos EQUAL -1)
      message(FATAL_ERROR "[install_consumer] ${f} refers to '${leak}': the export is not relocatable")
    endif()
  endforeach()
endforeach()
message(STATUS "[install_consumer] layout OK: ${installed_headers}")

# --- 3. find_package(tesslod CONFIG) consumer -------------------------------------------------
set(cm_build "${TLOD_PREFIX}/consumer-build")
set(gen_args "")
if(CONSUMER_GENERATOR)
  list(APPEND gen_args -G "${CONSUMER_GENERATOR}")
  if(CONSUMER_MAKE_PROGRAM)
    list(APPEND gen_args "-DCMAKE_MAKE_PROGRAM=${CONSUMER_MAKE_PROGRAM}")
  endif()
endif()
run("configure consumer (find_package)" "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${cm_build}" ${gen_args}
    "-DCMAKE_PREFIX_PATH=${TLOD_PREFIX}"
    "-DCMAKE_C_COMPILER=${CONSUMER_C_COMPILER}"
    "-DCMAKE_C_FLAGS=${CONSUMER_FLAGS}"
    "-DCMAKE_BUILD_TYPE=${TLOD_CONFIG}"
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)

# It must have found the package we just installed, not some other tesslod on the system.
file(STRINGS "${cm_build}/CMakeCache.txt" found_dir REGEX "^tesslod_DIR:")
string(REGEX REPLACE "^tesslod_DIR:[A-Z]+=" "" found_dir "${found_dir}")
file(REAL_PATH "${found_dir}" found_dir)
file(REAL_PATH "${lib}/cmake/tesslod" want_dir)
if(NOT found_dir STREQUAL want_dir)
  message(FATAL_ERROR "[install_consumer] consumer found tesslod in ${found_dir}, expected ${want_dir}")
endif()

run("build consumer (find_package)" "${CMAKE_COMMAND}" --build "${cm_build}" ${config_args})
set(cm_exe "${cm_build}/consumer")
if(NOT EXISTS "${cm_exe}" AND TLOD_CONFIG)
  set(cm_exe "${cm_build}/${TLOD_CONFIG}/consumer") # multi-config generators
endif()
run("run consumer (find_package)" "${cm_exe}")

# --- 4. pkg-config consumer -------------------------------------------------------------------
if(NOT PKG_CONFIG_EXECUTABLE OR NOT EXISTS "${PKG_CONFIG_EXECUTABLE}")
  message(FATAL_ERROR "[install_consumer] pkg-config not found (scripts/bootstrap installs it)")
endif()
set(ENV{PKG_CONFIG_PATH} "${lib}/pkgconfig")
message(STATUS "[install_consumer] PKG_CONFIG_PATH=$ENV{PKG_CONFIG_PATH}")
execute_process(COMMAND "${PKG_CONFIG_EXECUTABLE}" --modversion tesslod
                OUTPUT_VARIABLE pc_version OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT pc_version STREQUAL TLOD_VERSION)
  message(FATAL_ERROR "[install_consumer] pkg-config --modversion tesslod: '${pc_version}' (rc ${rc}), "
                      "expected ${TLOD_VERSION}")
endif()
execute_process(COMMAND "${PKG_CONFIG_EXECUTABLE}" --cflags --libs tesslod
                OUTPUT_VARIABLE pc_flags OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "[install_consumer] pkg-config --cflags --libs tesslod failed (${rc})")
endif()
message(STATUS "[install_consumer] pkg-config --cflags --libs tesslod: ${pc_flags}")
# Everything the static libraries need is in Libs (not Libs.private): libm, pthreads, and the GL
# library when the GL backend is built.
set(pc_need -lm)
if(TLOD_BACKEND_GL)
  list(APPEND pc_need -ltesslod_gl -lOpenGL)
endif()
separate_arguments(pc_got UNIX_COMMAND "${pc_flags}")
foreach(flag IN LISTS pc_need)
  if(NOT flag IN_LIST pc_got)
    message(FATAL_ERROR "[install_consumer] pkg-config --libs tesslod lacks ${flag}: ${pc_flags}")
  endif()
endforeach()
if(NOT "-lpthread" IN_LIST pc_got AND NOT "-pthread" IN_LIST pc_got)
  message(FATAL_ERROR "[install_consumer] pkg-config --libs tesslod lacks -lpthread / -pthread: ${pc_flags}")
endif()
set(pc_sources "${CONSUMER_SOURCE_DIR}/consumer.c")
set(pc_defs "")
if(TLOD_BACKEND_GL)
  # The consumer's own EGL context: egl.pc (libegl-dev). libOpenGL comes from tesslod.pc alone.
  execute_process(COMMAND "${PKG_CONFIG_EXECUTABLE}" --cflags --libs egl
                  OUTPUT_VARIABLE egl_flags OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "[install_consumer] pkg-config --cflags --libs egl failed (${rc}; libegl-dev)")
  endif()
  string(APPEND pc_flags " ${egl_flags}")
  list(APPEND pc_sources "${CONSUMER_SOURCE_DIR}/consumer_gl.c")
  set(pc_defs -DTLOD_CONSUMER_GL=1)
endif()
string(FIND "${pc_flags}" "-I${TLOD_PREFIX}/" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "[install_consumer] tesslod.pc does not point into ${TLOD_PREFIX}")
endif()
separate_arguments(pc_args UNIX_COMMAND "${pc_flags}")
set(pc_exe "${TLOD_PREFIX}/consumer-pkgconfig")
# Libraries after the source file: static link order.
run("build consumer (pkg-config)" "${CONSUMER_C_COMPILER}" -std=c11 -Wall -Wextra -Wpedantic -Werror ${consumer_flags}
    ${pc_defs} ${pc_sources} -o "${pc_exe}" ${pc_args} ${consumer_flags})
run("run consumer (pkg-config)" "${pc_exe}")

message(STATUS "[install_consumer] OK: find_package and pkg-config consumers built and ran against ${TLOD_PREFIX}")
