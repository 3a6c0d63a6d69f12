// The design's assertions (docs/rtl.md, "Assertions"): immediate assertions
// in the clocked processes and a few concurrent ones, checked when the
// design is verilated with --assert (every configuration of this build,
// rtl_model/CMakeLists.txt) and left out of synthesis (`ifndef SYNTHESIS
// around each; yosys defines SYNTHESIS). They only read the design's
// signals: with or without them the design computes the same values in the
// same cycles.
//
// `IMAP_FAIL(name, pe) is the action of a failing assertion: with
// IMAP_ASSERT_HOOK (the verilated testbench build) a DPI-C call into the
// SystemC testbench (rtl_model/verif/imap_dpi_pkg.sv, cosim/src/dpi.cpp),
// which stops the run with a report (cycle, PC, PE, assertion name) and the
// waves of the cycles before it; without it (another simulator, a bare
// lint of rtl_model/hdl) the standard $error. `pe` is the PE's index, -1
// for the CP and the array-wide checks.
`ifndef IMAP_ASSERT_SVH
`define IMAP_ASSERT_SVH
`ifdef IMAP_ASSERT_HOOK
`define IMAP_FAIL(name, pe) imap_dpi_pkg::imap_rtl_assert(`"name`", int'(pe))
`else
`define IMAP_FAIL(name, pe) $error("assertion %s failed (PE %0d)", `"name`", int'(pe))
`endif
`endif
