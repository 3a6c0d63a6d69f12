; Stand-alone forward pass: the host fills every PE's line buffers and reads
; the pointer columns back (local memory, or external for spilled columns).
; Lines on PEs 2y / 2y+1 (bidir) or y (single). Used by the firmware tests;
; the full program (dp.s) runs the same macros after its video re-layout.
.include "dp_setup.inc"
.include "dp_init.inc"
.include "dp_forward.inc"
        FWD_BODIES
        cli     c8, #0
        cli     c9, #HB
        DP_SETUP
        DP_INIT
.phase forward
        ld      r15, [#K_KIND]
        PLAN_FORWARD
        halt
