# cmake -DDIR=<folder> -P typed_messages.cmake
# Issue 12 point 3: hub code reads Commands and writes States through the generated typed classes
# (<idl>_typed.h) only. Fails, naming file and line, on any C/C++ source under DIR that uses
# const_cast, a char pointer, or idlc's sequence internals (_buffer, _length).
file(GLOB_RECURSE sources "${DIR}/*.cc" "${DIR}/*.h" "${DIR}/*.c" "${DIR}/*.cpp")
if(NOT sources)
  message(FATAL_ERROR "no C/C++ sources under ${DIR}: nothing checked")
endif()
set(found "")
foreach(source IN LISTS sources)
  file(STRINGS "${source}" lines)
  set(number 0)
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    # The member names only (not text_buffer.h): a non-identifier character on both sides.
    if(line MATCHES "const_cast|char[ \t]*\\*|(^|[^A-Za-z0-9_])_(buffer|length)([^A-Za-z0-9_]|$)")
      string(APPEND found "\n  ${source}:${number}: ${line}")
    endif()
  endforeach()
endforeach()
if(found)
  message(FATAL_ERROR "use the typed message classes (firmware/msgs/README.md, \"Typed accessors\") "
                      "instead of:${found}")
endif()
list(LENGTH sources count)
message(STATUS "${count} files under ${DIR}: no const_cast, char*, _buffer or _length")
