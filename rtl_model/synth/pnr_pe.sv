// Place-and-route harness of one PE (scripts/rtl-pnr.sh, docs/rtl.md,
// "Place and route (iCE40)"): not part of the design. imap_pe has about
// 250 input and 100 output bits, more than an iCE40 package has pins, so
// this harness feeds every input bit from one serial shift register (pin
// sin) and folds every output bit into one registered XOR (pin sout).
// Nothing of the PE is constant and no output is unused, so synthesis
// removes nothing of it; the harness adds WI flip-flops (the shift
// register), the XOR tree and one flip-flop.
// The PE's other parameters stay at their defaults (NREGS 16, MASK_DEPTH 8,
// XROWS 8: the row ports below are 8 bytes).
module imap_pnr_pe #(parameter int MEM_BYTES = 1024) (input logic clk, sin, output logic sout);
  localparam int XROWS = 8;
  imap_pkg::cw_t cw;
  imap_pkg::cwx_t cwx;
  logic [31:0] cw_pre;
  logic [15:0] pe_index;
  logic [7:0] nb_lo, nb_hi;
  logic [XROWS*8-1:0] row_in;
  localparam int WI = $bits(cw) + $bits(cwx) + 32 + 16 + 8 + 8 + XROWS * 8;
  logic [WI-1:0] sh;
  always_ff @(posedge clk) sh <= {sh[WI-2:0], sin};
  assign {cw, cwx, cw_pre, pe_index, nb_lo, nb_hi, row_in} = sh;

  logic [7:0] ring_q;
  logic [2:0] st_q;
  logic [XROWS*8-1:0] row_q;
  logic [15:0] xoff_q;
  imap_pe #(.MEM_BYTES(MEM_BYTES)) u_pe (.*);
  always_ff @(posedge clk) sout <= ^{ring_q, st_q, row_q, xoff_q};
endmodule
