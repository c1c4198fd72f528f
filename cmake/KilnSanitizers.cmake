# KILN_SANITIZE: "", "address" (ASan + UBSan) or "thread" (TSan). Applied to every target.
set(KILN_SANITIZE "" CACHE STRING "Sanitizer build: empty, address (ASan+UBSan) or thread")
if(KILN_SANITIZE STREQUAL "address")
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
elseif(KILN_SANITIZE STREQUAL "thread")
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
