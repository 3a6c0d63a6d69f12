# How one configuration of the design is verilated: the sources, Verilator's
# arguments and the C++ optimisation of the generated model. Included by
# this build (rtl_model/CMakeLists.txt) and by the project of an on-demand
# configuration (rtl_model/cache/CMakeLists.txt), which imapsim writes and
# builds at run time from the copy of these files embedded in it
# (docs/rtl.md, "Any configuration on demand"): both verilate the same way.

# The design (synthesizable; synthesis reads only these), the DPI package
# (read first: the design's assertions call it, IMAP_ASSERT_HOOK) and the
# verification sources around the design (board model, the CP's retire
# monitor, the testbench top imap_tb, Verilator's top module).
set(IMAP_RTL_HDL_FILES imap_pkg.sv imap_pe.sv imap_array.sv imap_cp.sv imap_perf.sv imap_top.sv)
set(IMAP_RTL_HDL_HEADERS imap_params.svh imap_ports.svh imap_assert.svh imap_mutants.svh)
set(IMAP_RTL_DPI_FILE imap_dpi_pkg.sv)
set(IMAP_RTL_VERIF_FILES imap_board.sv imap_cp_monitor.sv imap_tb.sv)

# imap_rtl_verilate(TARGET PREFIX HDL_DIR VERIF_DIR PES MEM EXT VARIANT ASSERT COVERAGE)
# VARIANT: fast (no tracing), vcd, fst (tracing compiled in, off until a run
# asks), mut (the planted bugs of the mutation check selectable) or mutfst
# (mut with FST tracing compiled in: waves of the window before a failure).
function(imap_rtl_verilate target prefix hdl verif pes mem ext variant assert coverage)
  set(extra "")
  # (-Werror-USERFATAL: an elaboration check of the design stops the build)
  set(args -I${hdl} -O3 --x-assign fast --x-initial 0 -Wall -Wno-fatal -Werror-USERFATAL
      -Wno-DECLFILENAME -Wno-UNUSEDSIGNAL -Wno-UNUSEDPARAM -Wno-BLKSEQ -Wno-VARHIDDEN)
  if(variant STREQUAL "vcd")
    set(extra TRACE TRACE_STRUCTS)
  elseif(variant STREQUAL "fst")
    set(extra TRACE_FST TRACE_STRUCTS)
  elseif(variant STREQUAL "mut")
    list(APPEND args +define+IMAP_MUTANTS)
  elseif(variant STREQUAL "mutfst")
    set(extra TRACE_FST TRACE_STRUCTS)
    list(APPEND args +define+IMAP_MUTANTS)
  endif()
  if(assert)
    list(APPEND args --assert +define+IMAP_ASSERT_HOOK)
  endif()
  if(coverage)
    list(APPEND extra COVERAGE)
  endif()
  # The generated C++ is Verilator's: no project warnings, and no sanitizer
  # instrumentation (the sanitizer build instruments the testbench around
  # it; the model stays fast enough for the suite).
  set(opt_fast -O2 -w)
  set(opt_slow -O1 -w)
  if(CMAKE_BUILD_TYPE STREQUAL "Asan")
    list(APPEND opt_fast -fno-sanitize=all)
    list(APPEND opt_slow -fno-sanitize=all)
  endif()
  set(sources ${verif}/${IMAP_RTL_DPI_FILE})
  foreach(f ${IMAP_RTL_HDL_FILES})
    list(APPEND sources ${hdl}/${f})
  endforeach()
  foreach(f ${IMAP_RTL_VERIF_FILES})
    list(APPEND sources ${verif}/${f})
  endforeach()
  verilate(${target} SYSTEMC ${extra}
    PREFIX ${prefix}
    TOP_MODULE imap_tb
    SOURCES ${sources}
    VERILATOR_ARGS ${args} -GP=${pes} -GMEM_BYTES=${mem} -GEXT_BYTES=${ext}
    OPT_FAST ${opt_fast}
    OPT_SLOW ${opt_slow}
    OPT_GLOBAL ${opt_slow})
  # Verilator counts the trace's per-cycle dump functions (__Trace__N.cpp) as
  # fast code, but they run only while a run writes waves, and they take a
  # quarter of a traced configuration's compile time: compiled like the slow
  # code (the later flag wins; docs/performance.md). The file lists are verilate()'s, read back from
  # the copy it includes (written when it verilated, at configure time).
  include("${CMAKE_CURRENT_BINARY_DIR}/CMakeFiles/${target}.dir/${prefix}.dir/${prefix}_copy.cmake")
  list(JOIN opt_slow " " trace_flags)
  foreach(f ${${prefix}_SUPPORT_FAST})
    if(f MATCHES "__Trace__[0-9]+\\.cpp$")
      set_property(SOURCE "${f}" APPEND_STRING PROPERTY COMPILE_FLAGS " ${trace_flags}")
    endif()
  endforeach()
endfunction()
