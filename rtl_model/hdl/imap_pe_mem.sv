`include "imap_assert.svh"
// The local memory of one PE (docs/isa.md 1.1, docs/rtl.md "The PE's local
// memory"): BYTES bytes as BANKS byte-wide banks, byte a in bank a mod BANKS
// at index a / BANKS. Each bank is a plain synchronous RAM of one read and
// one write port (the shape synthesis maps to a block RAM: on iCE40 one
// SB_RAM40_4K per bank up to 512 bytes). Together the banks give the PE's
// two row ports:
//   - read: at an edge with re, the BANKS bytes from ra (any alignment; a
//     byte past the end of the memory reads an unspecified value), held on
//     rd until the next read. A byte written at the same edge reads as
//     written (write-first: one bypass register per bank), which is the
//     PE's preload rule "the preloads see the memory as this edge leaves
//     it".
//   - write: at an edge, byte i of wd to address wa + i for each we[i]
//     (a row of the video / transfer bus, or one st / stx byte as byte 0).
module imap_pe_mem
#(
    parameter int BYTES  /*verilator public*/ = 1024,  // the backdoor reads it
    parameter int BANKS = 8,
    localparam int AW = $clog2(BYTES > 1 ? BYTES : 2)
) (
    input logic clk,
    input logic [15:0] pe_index,  // for assertion reports only
    input logic re,
    input logic [AW-1:0] ra,
    input logic [BANKS-1:0] we,
    input logic [AW-1:0] wa,
    input logic [BANKS*8-1:0] wd,
    output logic [BANKS*8-1:0] rd
);
  localparam int LB = $clog2(BANKS);
  localparam int AI = AW > LB ? AW : LB;  // address width inside (at least the bank bits)
  localparam int DEPTH = (BYTES + BANKS - 1) / BANKS;
  localparam int IW = $clog2(DEPTH > 1 ? DEPTH : 2);

  logic [AI-1:0] rai, wai;
  assign rai = AI'(ra);
  assign wai = AI'(wa);
  logic [LB-1:0] ra_lo_q;  // bank of byte 0 of the row on rd
  logic [7:0] q[BANKS];  // each bank's read byte

  for (genvar k = 0; k < BANKS; k++) begin : g_bank
    // The testbench's backdoor reads and clears b (simulation only).
    logic [7:0] b[DEPTH] /*verilator public_flat_rw*/;
    logic [LB-1:0] ir, iw;  // the byte of the read / write row that falls in this bank
    logic [AI:0] ar, aw;  // its address
    logic [IW-1:0] xr, xw;  // its index in this bank
    logic wek;
    logic [7:0] wdk, bq, byp_d;
    logic byp;
    always_comb begin
      ir = LB'(k) - rai[LB-1:0];
      iw = LB'(k) - wai[LB-1:0];
      ar = {1'b0, rai} + (AI + 1)'(ir);
      aw = {1'b0, wai} + (AI + 1)'(iw);
      // the row's byte in bank k lies in the row's first word, or in the
      // next one when k is below the row's first bank
      /* verilator lint_off CMPCONST */  // constant for the last bank
      xr = IW'(rai >> LB) + IW'(LB'(k) < rai[LB-1:0]);
      xw = IW'(wai >> LB) + IW'(LB'(k) < wai[LB-1:0]);
      /* verilator lint_on CMPCONST */
      wek = we[iw];
      wdk = wd[iw*8+:8];
    end
    always_ff @(posedge clk) begin
      if (wek) b[xw] <= wdk;
      // (on a read of the byte being written the bypass below gives the
      // byte, so what the RAM returns then is left open: 'x)
      if (re) bq <= (wek && xw == xr) ? 8'hxx : b[xr];
    end
    // write-first: the byte written at the read edge replaces the old one
    always_ff @(posedge clk)
      if (re) begin
        byp <= wek && xw == xr;
        byp_d <= wdk;
      end
    assign q[k] = byp ? byp_d : bq;
`ifndef SYNTHESIS
    // A write stays inside the memory (the CP faults a transfer or an
    // address past the end before any byte is written).
    always_ff @(posedge clk)
      a_pe_mem_write :
      assert (!wek || aw < (AI + 1)'(BYTES))
      else `IMAP_FAIL(a_pe_mem_write, pe_index);
    // A preloaded byte inside the memory equals the memory as the read edge
    // left it (checked at the next edge, before that edge's writes).
    logic chk;
    logic [IW-1:0] xr_q;
    always_ff @(posedge clk) begin
      if (chk)
        a_pe_preload_mem :
        assert (q[k] == b[xr_q])
        else `IMAP_FAIL(a_pe_preload, pe_index);
      chk <= re && ar < (AI + 1)'(BYTES);
      if (re) xr_q <= xr;
    end
`endif
  end

  always_ff @(posedge clk) if (re) ra_lo_q <= rai[LB-1:0];
  always_comb for (int i = 0; i < BANKS; i++) rd[i*8+:8] = q[LB'(ra_lo_q+LB'(i))];

endmodule
