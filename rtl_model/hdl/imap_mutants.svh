// The mutation check (docs/rtl.md, "Mutation check"): with IMAP_MUTANTS
// defined, the design gets a `mutant` input and `IMAP_MUT(n) is true when
// planted bug n is selected (ids and names: rtl_model/src/config.cpp,
// imap::rtl::mutants()). Without it every `IMAP_MUT(n) is 0 and the
// mutation logic does not exist (the production configurations, synthesis).
`ifndef IMAP_MUTANTS_SVH
`define IMAP_MUTANTS_SVH
`ifdef IMAP_MUTANTS
`define IMAP_MUT(n) (mutant == 8'd``n)
`else
`define IMAP_MUT(n) 1'b0
`endif
`endif
