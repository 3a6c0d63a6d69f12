; One node of the forward pass (NODE, dp_forward.inc) in a phase of its own,
; for the machine bound of the forward pass (firmware/src/bounds.cpp,
; docs/firmware.md section 11): the phase's cycles on the cost table of the
; run are the cycles per valid state the bound charges. The addresses are
; those of level 0 of a column; the values read do not matter.
.include "dp_setup.inc"
.include "dp_forward.inc"
.include "census.inc"
        cli     c0, #0
        cli     c1, #0
        cli     c2, #0
.phase node
        NODE    0, r1, r2, r3, r4
.if AGGR
; with a window the node adds a precomputed sum; the state's own pixel
; pair's match cost, computed once somewhere, is part of its work too
        ld      r7, [c2]
.if KC > 0
        WM_CENSUS 0, r1, r2, 0
.endif
.set WBO 0
.set WBU 0
        WM_ADD  r1, r2
.endif
.phase probe_end
        halt
