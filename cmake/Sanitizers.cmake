# Sanitizer builds: -DTESSERA_SANITIZE=address,undefined (or thread) instruments
# every target, ours and the tests, so a bad input that corrupts memory or hits
# undefined behaviour fails the test suite instead of passing by luck.
# Undefined behaviour aborts at the first report (-fno-sanitize-recover), so a
# test that triggers it fails rather than printing and going on.
# Libraries from Debian packages (oneTBB, OpenImageIO) stay uninstrumented.
set(TESSERA_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined or thread (empty: none)")

if(TESSERA_SANITIZE)
  if(TESSERA_SANITIZE MATCHES "thread" AND TESSERA_SANITIZE MATCHES "address")
    message(FATAL_ERROR "TESSERA_SANITIZE: thread and address cannot be combined")
  endif()
  message(STATUS "Sanitizers: ${TESSERA_SANITIZE}")
  add_compile_options(-fsanitize=${TESSERA_SANITIZE} -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=${TESSERA_SANITIZE})
  if(TESSERA_SANITIZE MATCHES "undefined")
    add_compile_options(-fno-sanitize-recover=undefined)
  endif()
endif()
