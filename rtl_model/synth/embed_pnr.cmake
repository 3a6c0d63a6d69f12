# Writes OUT, a C++ file returning the place-and-route figures IN
# (rtl_model/synth/pnr_ice40.json, written by scripts/rtl-pnr.sh and checked
# in), compiled into imap_rtl_catalog (cosim/src/pnr.cpp parses them).
file(READ ${IN} j)
file(WRITE ${OUT}.tmp "// Generated from rtl_model/synth/pnr_ice40.json (scripts/rtl-pnr.sh).\nnamespace imap::rtl::detail {\nconst char* pnr_ice40_json() {\n    return R\"json(${j})json\";\n}\n}\n")
file(RENAME ${OUT}.tmp ${OUT})
