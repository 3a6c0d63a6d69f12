; Stand-alone DP core: the host fills every PE's line buffers, the program
; runs set-up, start column, forward pass, backtrack with vote and merge;
; the host reads pixel x of line y from MAP on PE 2y + (x & 1) (bidir) or y.
.include "dp_setup.inc"
.include "dp_init.inc"
.include "dp_forward.inc"
.include "dp_back.inc"
        FWD_BODIES
        jmp     start
        BT_COLUMN
.if BSTEP
        BT_WALK
.endif
start:
        cli     c8, #0
        cli     c9, #HB
        DP_SETUP
        DP_INIT
        DP_FORWARD
        DP_CLEARMAP
        DP_BACKTRACK
        DP_MERGE
        halt
