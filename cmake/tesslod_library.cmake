# tlod_add_library(NAME tlod_core ALIAS core DIR core [DEPS ...])
# A tesslod library: sources from DIR/src, public headers from DIR/include,
# exported as tesslod::ALIAS.
function(tlod_add_library)
  cmake_parse_arguments(A "" "NAME;ALIAS;DIR" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${A_DIR}/src/*.c)
  add_library(${A_NAME} STATIC ${srcs})
  add_library(tesslod::${A_ALIAS} ALIAS ${A_NAME})
  set_target_properties(${A_NAME} PROPERTIES EXPORT_NAME ${A_ALIAS} OUTPUT_NAME tesslod_${A_ALIAS})
  target_include_directories(${A_NAME}
    PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/${A_DIR}/include>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${PROJECT_SOURCE_DIR}/${A_DIR}/src)
  target_link_libraries(${A_NAME} PUBLIC ${A_DEPS} PRIVATE ${A_PRIVATE_DEPS} $<BUILD_INTERFACE:tlod_build_flags>)
  set_property(GLOBAL APPEND PROPERTY TLOD_INSTALL_TARGETS ${A_NAME})
  set_property(GLOBAL APPEND PROPERTY TLOD_INSTALL_HEADER_DIRS ${PROJECT_SOURCE_DIR}/${A_DIR}/include/tesslod)
endfunction()
