// The clock, reset and mutant-select ports that the chip's modules share,
// declared once: `IMAP_CLOCK_PORTS (clk, rst_n) and `IMAP_MUTANT_PORT (the
// planted-bug select of the mutation check, docs/rtl.md; present only in a
// build with IMAP_MUTANTS), each ending with a comma, at the head of a
// module's port list:
//   module m #(...) (
//     `IMAP_CLOCK_PORTS
//     input ... );
`ifndef IMAP_PORTS_SVH
`define IMAP_PORTS_SVH
`ifdef IMAP_MUTANTS
`define IMAP_MUTANT_PORT input logic [7:0] mutant,
`else
`define IMAP_MUTANT_PORT
`endif
`define IMAP_CLOCK_PORTS input logic clk, input logic rst_n, `IMAP_MUTANT_PORT
`endif
