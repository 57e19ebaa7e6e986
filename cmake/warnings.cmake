# Flags live on an INTERFACE target, never in CMAKE_CXX_FLAGS.
add_library(dynmesh_options INTERFACE)
target_compile_options(dynmesh_options INTERFACE -Wall -Wextra -Wpedantic -Wno-unused-parameter
                                            -Wno-missing-field-initializers)
if(DYNMESH_WERROR)
  target_compile_options(dynmesh_options INTERFACE -Werror)
endif()
if(DYNMESH_SANITIZE)
  string(REPLACE ";" "," _san "${DYNMESH_SANITIZE}")
  target_compile_options(dynmesh_options INTERFACE -fsanitize=${_san} -fno-omit-frame-pointer
                                                   -fno-sanitize-recover=undefined)
  target_link_options(dynmesh_options INTERFACE -fsanitize=${_san})
endif()
