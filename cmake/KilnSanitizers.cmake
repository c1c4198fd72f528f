# KILN_SANITIZE: "", "address" (ASan + UBSan) or "thread" (TSan). Applied to every target.
set(KILN_SANITIZE "" CACHE STRING "Sanitizer build: empty, address (ASan+UBSan) or thread")
if(KILN_SANITIZE STREQUAL "address")
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
elseif(KILN_SANITIZE STREQUAL "thread")
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  # GCC 12's TSan instrumentation makes its object-size warnings misread std::string's small buffer in
  # `a + "/" + b` (about 25 warnings in the test files, none in other builds; silencing -Warray-bounds alone moves
  # them to -Wstringop-overflow); the GCC manual warns that sanitizers raise false positives.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-array-bounds -Wno-stringop-overflow -Wno-stringop-overread)
  endif()
  add_link_options(-fsanitize=thread)
endif()
