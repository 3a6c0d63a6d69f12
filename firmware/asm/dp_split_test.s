; Stand-alone forward pass with each kind's columns split over the PE pair
; (dp_split.inc): the host fills every PE's line buffers (its own kind's R'
; and L' bytes and its partner kind's) and reads the steps' pointer bytes
; back. Lines on PEs 2y / 2y+1 (bidir). Used by the firmware tests.
.include "dp_setup.inc"
.include "dp_forward.inc"
.include "dp_split.inc"
        FWD_BODIES
        SPLIT_BODIES
        cli     c8, #0
        cli     c9, #HB
        DP_SETUP
.phase forward
        ld      r15, [#K_KIND]
        PLAN_SPLIT
        halt
