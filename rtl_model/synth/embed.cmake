# Writes OUT, a C++ file with the yosys statistics (JSON) of the PE and the
# CP, compiled into imap_rtl_catalog (cosim/src/synth.cpp reads them).
foreach(f pe pe.mem cp cp.mem)
  file(READ ${DIR}/${f}.json j)
  string(MAKE_C_IDENTIFIER ${f} id)
  set(body "${body}const char* synth_${id}_json() {\n    return R\"json(${j})json\";\n}\n")
endforeach()
file(WRITE ${OUT}.tmp "// Generated from the yosys synthesis of this build (rtl_model/synth).\nnamespace imap::rtl::detail {\n${body}}\n")
file(RENAME ${OUT}.tmp ${OUT})
