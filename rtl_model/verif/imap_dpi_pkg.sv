// The testbench's DPI-C imports (verification only; the design in
// rtl_model/hdl calls one, imap_rtl_assert, and only through the
// IMAP_ASSERT_HOOK define of its assertion macro, imap_assert.svh): the
// trace port (the CP's retire record and
// param-block writes, reported by the retire monitor imap_cp_monitor.sv
// bound into the CP), the fault report (same monitor) and the video line
// port of the board model (imap_board.sv: camera / display). Each is
// implemented by the SystemC testbench (dpi.cpp); the trace calls are made
// only when the testbench has set the `trace` strap. The PE state
// (registers, flags, memories) is not reported through DPI: the lockstep
// checker reads it from the design's public state elements at each retire
// (rtl_model/verif/checker.cpp).
package imap_dpi_pkg;
  // One retired instruction (the CP's retire record): index counts every
  // retired instruction from 0, cyc is the machine cycle at its issue and
  // cyc_end after its last cycle. cwr: CP register written (creg >= 0).
  import "DPI-C" function void imap_rtl_retire(
    input longint index, input int pc, input longint word, input longint cyc,
    input longint cyc_end, input int phase, input int creg, input int cval,
    input int msp, input int csp, input int active, input bit halted);
  // A CP param-block word written (cst).
  import "DPI-C" function void imap_rtl_param_write(input int addr, input int value);
  // The fault that stopped the machine (code: imap_pkg::fault_t).
  import "DPI-C" function void imap_rtl_fault(
    input int code, input int pc, input longint cyc, input int pe, input longint addr);

  // A failing assertion of the design (rtl_model/hdl/imap_assert.svh, with
  // IMAP_ASSERT_HOOK): its name and the PE (-1: the CP, array-wide).
  import "DPI-C" function void imap_rtl_assert(input string name, input int pe);

  // Video line port: status 0 = ok, 1 = no image on that port, 2 = line
  // outside the image. vid_check is asked when vin / vout enters execute;
  // vid_pixel returns pixel x of line y (0 beyond the width); vid_put
  // writes one pixel of an output line (ignored beyond the width).
  import "DPI-C" function int imap_rtl_vid_check(input int dir_out, input int port, input int y);
  import "DPI-C" function int imap_rtl_vid_pixel(input int port, input int y, input int x);
  // the camera's timing: the machine cycle at which pixels x.. x + P - 1 of
  // line y have arrived (0 = already there: an ideal camera)
  import "DPI-C" function longint imap_rtl_vid_ready(input int port, input int y, input int x);
  import "DPI-C" function void imap_rtl_vid_put(input int port, input int y, input int x,
                                                 input int val);
endpackage
