# Install rules and package files for every library registered by tlod_add_library()
# (cmake/tesslod_library.cmake). Included at the END of the top-level CMakeLists.txt:
# the global properties TLOD_INSTALL_TARGETS and TLOD_INSTALL_HEADER_DIRS are filled as
# the subdirectories are added, so every add_subdirectory() must come before this file.
#
# Installed layout (paths relative to the install prefix):
#   ${CMAKE_INSTALL_LIBDIR}/libtesslod_<alias>.a         imported as tesslod::<alias>
#   ${CMAKE_INSTALL_INCLUDEDIR}/tesslod/*.h               public headers only
#   ${CMAKE_INSTALL_LIBDIR}/cmake/tesslod/                tesslodConfig.cmake, tesslodConfigVersion.cmake,
#                                                         tesslodTargets[-<config>].cmake
#   ${CMAKE_INSTALL_LIBDIR}/pkgconfig/tesslod.pc          relocatable (prefix from ${pcfiledir})
#   ${CMAKE_INSTALL_DATADIR}/tesslod/glsl/*.glsl          patch evaluation for engines' shaders
#                                                         (docs/shaders.md)
#
# Consumers:
#   find_package(tesslod 1.0 CONFIG REQUIRED)  # optionally COMPONENTS core lod cpu
#   target_link_libraries(app PRIVATE tesslod::cpu)
# or
#   cc app.c $(pkg-config --cflags --libs tesslod)
#
# tlod_build_flags (warnings, -ffp-contract=off, sanitizers) is linked as
# $<BUILD_INTERFACE:tlod_build_flags>, so it is not part of the export set and the
# installed targets carry none of the project's private build flags.
include_guard(GLOBAL)
include(CMakePackageConfigHelpers)

get_property(_tlod_targets GLOBAL PROPERTY TLOD_INSTALL_TARGETS)
get_property(_tlod_header_dirs GLOBAL PROPERTY TLOD_INSTALL_HEADER_DIRS)
if(NOT _tlod_targets)
  message(FATAL_ERROR "tesslod_install.cmake: TLOD_INSTALL_TARGETS is empty. It must be included after "
                      "every add_subdirectory() that calls tlod_add_library().")
endif()
list(REMOVE_DUPLICATES _tlod_targets)
list(REMOVE_DUPLICATES _tlod_header_dirs)

set(TLOD_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/tesslod")
set(TLOD_INSTALL_PKGCONFIGDIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
set(_tlod_pkg_dir "${PROJECT_BINARY_DIR}/tesslod-package")

# --- Libraries and the export set ----------------------------------------------------------
install(TARGETS ${_tlod_targets}
  EXPORT tesslodTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

install(EXPORT tesslodTargets
  NAMESPACE tesslod::
  FILE tesslodTargets.cmake
  DESTINATION ${TLOD_INSTALL_CMAKEDIR})

# --- Public headers ------------------------------------------------------------------------
# Every registered dir is <module>/include/tesslod; they all merge into include/tesslod/.
# Two modules shipping a header with the same name would silently overwrite each other.
set(_tlod_header_names "")
foreach(_dir IN LISTS _tlod_header_dirs)
  if(NOT IS_DIRECTORY "${_dir}")
    message(FATAL_ERROR "tesslod_install.cmake: registered header dir ${_dir} does not exist")
  endif()
  file(GLOB _headers RELATIVE "${_dir}" "${_dir}/*.h")
  foreach(_h IN LISTS _headers)
    if(_h IN_LIST _tlod_header_names)
      message(FATAL_ERROR "tesslod_install.cmake: two modules install tesslod/${_h} (second one: ${_dir})")
    endif()
    list(APPEND _tlod_header_names "${_h}")
  endforeach()
endforeach()
install(DIRECTORY ${_tlod_header_dirs}
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h")

# --- GLSL for engines' own shaders (docs/shaders.md) ---------------------------------------
# layout.h is C and GLSL; installed as layout.glsl, so the include directory holds only the
# public C headers.
get_property(_tlod_glsl GLOBAL PROPERTY TLOD_GLSL_FILES)
set(TLOD_INSTALL_GLSLDIR "${CMAKE_INSTALL_DATADIR}/tesslod/glsl")
foreach(_f IN LISTS _tlod_glsl)
  get_filename_component(_name "${_f}" NAME)
  string(REGEX REPLACE "\\.h$" ".glsl" _name "${_name}")
  install(FILES "${_f}" DESTINATION ${TLOD_INSTALL_GLSLDIR} RENAME "${_name}")
endforeach()

# --- CMake package files -------------------------------------------------------------------
set(TLOD_PACKAGE_COMPONENTS "")
foreach(_t IN LISTS _tlod_targets)
  get_target_property(_export_name ${_t} EXPORT_NAME)
  if(NOT _export_name)
    set(_export_name ${_t})
  endif()
  list(APPEND TLOD_PACKAGE_COMPONENTS ${_export_name})
endforeach()

configure_package_config_file(
  "${PROJECT_SOURCE_DIR}/cmake/tesslodConfig.cmake.in"
  "${_tlod_pkg_dir}/tesslodConfig.cmake"
  INSTALL_DESTINATION ${TLOD_INSTALL_CMAKEDIR})
write_basic_package_version_file(
  "${_tlod_pkg_dir}/tesslodConfigVersion.cmake"
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMajorVersion)
install(FILES
  "${_tlod_pkg_dir}/tesslodConfig.cmake"
  "${_tlod_pkg_dir}/tesslodConfigVersion.cmake"
  DESTINATION ${TLOD_INSTALL_CMAKEDIR})

# --- pkg-config ----------------------------------------------------------------------------
# The libraries are static, so their own dependencies (GL, libm, pthreads) go into Libs, not
# Libs.private: `pkg-config --libs tesslod` must link without --static.
# Link order: dependents first. Libraries are registered after the libraries they depend on
# (core, lod, cpu), so the reversed registration order is a valid static link order.
set(TLOD_PC_LIBS "")
set(_tlod_reversed ${_tlod_targets})
list(REVERSE _tlod_reversed)
foreach(_t IN LISTS _tlod_reversed)
  get_target_property(_out ${_t} OUTPUT_NAME)
  if(NOT _out)
    set(_out ${_t})
  endif()
  string(APPEND TLOD_PC_LIBS " -l${_out}")
endforeach()
string(STRIP "${TLOD_PC_LIBS}" TLOD_PC_LIBS)
if(CMAKE_THREAD_LIBS_INIT)
  set(TLOD_PC_THREAD_LIBS "${CMAKE_THREAD_LIBS_INIT}")
else()
  set(TLOD_PC_THREAD_LIBS "-lpthread") # glibc >= 2.34: pthreads are in libc; -lpthread is a harmless stub
endif()
# The GL backend links the GL library (OpenGL::OpenGL, GLVND's libOpenGL): it goes into Libs too,
# by name (-lOpenGL), so the file does not carry this machine's library path.
set(TLOD_PC_GL_LIBS "")
if(TARGET tlod_gl AND tlod_gl IN_LIST _tlod_targets)
  if(NOT OPENGL_opengl_LIBRARY)
    message(FATAL_ERROR "tesslod_install.cmake: the GL backend is built but OPENGL_opengl_LIBRARY is not set")
  endif()
  get_filename_component(_gl_name "${OPENGL_opengl_LIBRARY}" NAME_WE)
  string(REGEX REPLACE "^lib" "" _gl_name "${_gl_name}")
  set(TLOD_PC_GL_LIBS "-l${_gl_name} ")
endif()

# The Vulkan backend links the loader and glslang's static libraries (C++, so the C++ runtime
# too), by name in their static link order; Debian's glslang.pc names a library it does not ship.
set(TLOD_PC_VULKAN_LIBS "")
if(TARGET tlod_vulkan AND tlod_vulkan IN_LIST _tlod_targets)
  set(TLOD_PC_VULKAN_LIBS "-lvulkan -lglslang-default-resource-limits -lSPIRV -lglslang -lMachineIndependent ")
  string(APPEND TLOD_PC_VULKAN_LIBS "-lOGLCompiler -lOSDependent -lGenericCodeGen -lSPIRV-Tools-opt -lSPIRV-Tools ")
  string(APPEND TLOD_PC_VULKAN_LIBS "-lSPIRV-Tools-link -lstdc++ ")
endif()

# Relocatable: the prefix is derived from the .pc file's own location, so
# `cmake --install build --prefix /anywhere` (and DESTDIR) produce a working file.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(TLOD_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH _rel "/${TLOD_INSTALL_PKGCONFIGDIR}" "/")
  string(REGEX REPLACE "/$" "" _rel "${_rel}")
  set(TLOD_PC_PREFIX "\${pcfiledir}/${_rel}")
endif()
foreach(_kind LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_kind}}")
    set(TLOD_PC_${_kind} "${CMAKE_INSTALL_${_kind}}")
  else()
    set(TLOD_PC_${_kind} "\${prefix}/${CMAKE_INSTALL_${_kind}}")
  endif()
endforeach()
configure_file("${PROJECT_SOURCE_DIR}/cmake/tesslod.pc.in" "${_tlod_pkg_dir}/tesslod.pc" @ONLY)
install(FILES "${_tlod_pkg_dir}/tesslod.pc" DESTINATION ${TLOD_INSTALL_PKGCONFIGDIR})

unset(_tlod_glsl)
unset(_tlod_targets)
unset(_tlod_header_dirs)
unset(_tlod_header_names)
unset(_tlod_reversed)
unset(_gl_name)
