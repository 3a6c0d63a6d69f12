// The chip's size parameters (docs/rtl.md, "Configurations"), declared once
// for the modules that take all of them (imap_cp, imap_top, the testbench
// top imap_tb): included as the module's parameter port list,
//   module m #(
//   `include "imap_params.svh"
//   ) (...);
// and passed on to an instance with `IMAP_PARAMS_PASS:
//   m #(`IMAP_PARAMS_PASS) u_m (...);
`ifndef IMAP_PARAMS_PASS
`define IMAP_PARAMS_PASS .P(P), .MEM_BYTES(MEM_BYTES), .EXT_BYTES(EXT_BYTES), .NREGS(NREGS), .MASK_DEPTH(MASK_DEPTH), .CALL_DEPTH(CALL_DEPTH), .IMEM_WORDS(IMEM_WORDS), .XROWS(XROWS), .PHASES(PHASES)
`endif
    parameter int P = 8,  // PEs (pes)
    parameter int MEM_BYTES = 1024,  // local memory per PE (mem_bytes)
    parameter int EXT_BYTES = 65536,  // external memory per PE (ext_bytes)
    parameter int NREGS = 16,  // registers per PE (at least pe_regs)
    parameter int MASK_DEPTH = 8,  // mask stack (at least mask_depth)
    parameter int CALL_DEPTH = 16,  // return stack (at least call_depth)
    parameter int IMEM_WORDS = 65536,  // instruction memory
    parameter int XROWS = 8,  // rows per cycle of the transfer path (ext_bytes_per_cycle <= XROWS)
    parameter int PHASES = 256  // per-phase cycle counters
