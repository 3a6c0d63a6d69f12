// Board level: the external memory (SDRAM reached by block transfers,
// docs/isa.md 4.1 "External memory", organised as rows of one byte per PE)
// with the data side of the transfer engine, and the video line port
// (camera and display interface). The engine's control (setup cycles, the
// byte counter of the shared path, row completion) is in the CP's execute
// stage; this module moves the rows it names:
//   xe_pf  prefetch ext rows [xe_prow, xe_prow + XROWS) onto the row bus for
//          the PEs (xld; the external memory does not change during xld)
//   xe_wr  write xe_n ext rows [xe_wrow, ..) from the row read ports of the
//          PEs with M = 1 (xe_pm; xst)
// A prefetch at the edge of a write sees the written rows (bypass).
// The video port is the testbench's camera / display model (DPI): vid_open checks the line when vin / vout enters execute and, for
// vin, loads the line onto lane 0 of the row bus; vid_put sends the PEs'
// row to the output line when vout commits. A board model of the testbench
// (rtl_model/verif/imap_tb.sv instantiates it next to the chip), not synthesized.
module imap_board
#(
    parameter int P = 8,
    parameter int EXT_BYTES = 65536,
    parameter int XROWS = 8
) (
    input logic clk,
    input logic xe_pf,
    input logic [31:0] xe_prow,
    input logic xe_wr,
    input logic [31:0] xe_wrow,
    input logic [3:0] xe_n,
    input logic [P-1:0] xe_pm,
    input logic vid_open,
    input logic vid_out,
    input logic [0:0] vid_oport,
    input logic [31:0] vid_oy,
    input logic [31:0] vid_ox,
    input logic vid_put,
    input logic [0:0] vid_pport,
    input logic [31:0] vid_py,
    input logic [31:0] vid_px,
    input logic [P*XROWS*8-1:0] rrow,  // PE p: slice p
    output logic [P*XROWS*8-1:0] rbus,
    output logic [1:0] vid_status,
    output logic [63:0] vid_ready  // of the last vin's vid_open: cycle its pixels have arrived
);

  localparam int EXT_N = EXT_BYTES > 0 ? EXT_BYTES : 1;

  // byte (pe, a) at a * P + pe (address-major); public: the testbench's backdoor
  logic [7:0] ext[EXT_N*P]  /*verilator public_flat_rw*/;

  import imap_dpi_pkg::*;

  // The external memory is read and written only here (and by the
  // backdoor): blocking writes, so that a prefetch at the edge of a write
  // sees the new rows. The row bus is one register, written once per edge.
  always_ff @(posedge clk) begin
    logic [P*XROWS*8-1:0] nb;
    if (xe_wr)
      for (int i = 0; i < XROWS; i++)
        if (i < int'(xe_n) && xe_wrow + 32'(i) < 32'(EXT_BYTES))
          for (int p = 0; p < P; p++) begin
            if (xe_pm[p]) ext[(xe_wrow+32'(i))*32'(P)+32'(p)] = rrow[(p*XROWS+i)*8+:8];
          end
    if (xe_pf) begin
      for (int i = 0; i < XROWS; i++) begin
        logic [31:0] r;
        r = xe_prow + 32'(i);
        for (int p = 0; p < P; p++)
          nb[(p*XROWS+i)*8+:8] = (r < 32'(EXT_BYTES)) ? ext[r*32'(P)+32'(p)] : 8'h00;
      end
      rbus <= nb;
    end
    if (vid_open) begin
      int st;
      st = imap_rtl_vid_check(int'(vid_out), int'(vid_oport), int'(vid_oy));
      vid_status <= 2'(st);
      vid_ready <= vid_out ? 64'd0 : 64'(imap_rtl_vid_ready(int'(vid_oport), int'(vid_oy), int'(vid_ox)));
      if (!vid_out && st == 0) begin
        nb = '0;
        for (int p = 0; p < P; p++)
          nb[p*XROWS*8+:8] = 8'(imap_rtl_vid_pixel(int'(vid_oport), int'(vid_oy), int'(vid_ox) + p));
        rbus <= nb;
      end
    end
    if (vid_put)
      for (int p = 0; p < P; p++)
        imap_rtl_vid_put(int'(vid_pport), int'(vid_py), int'(vid_px) + p, int'(rrow[p*XROWS*8+:8]));
  end

endmodule
