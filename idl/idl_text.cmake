# Writes OUT: a C++ header holding the text of the IDL files IN (a ;-list, in dependency order) as one IDL document
# without its #include lines — the OMG IDL schema an MCAP recording or the Foxglove bridge advertises for every type
# ("omgidl" schema encoding: the reader finds the named struct and every type it uses in one text).
set(text "")
foreach(f ${IN})
  file(READ ${f} body)
  string(REGEX REPLACE "#include[^\n]*\n" "" body "${body}")
  get_filename_component(name ${f} NAME)
  string(APPEND text "// ${name}\n${body}\n")
endforeach()
file(WRITE ${OUT}.tmp "#pragma once\n// Generated at build time by idl/idl_text.cmake from idl/twinslam/*.idl. Do not edit.\n"
     "#include <string_view>\nnamespace twinslam::msg {\ninline constexpr std::string_view kIdlText = R\"twinslam_idl(${text})twinslam_idl\";\n}\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
