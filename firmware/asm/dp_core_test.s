; Stand-alone DP core: the host fills every PE's line buffers, the program
; runs set-up, start column, forward pass, vote + backtrack and merge, and
; the host reads the output lines from MAP (right-wavefront PEs in bidir).
.include "dp_init.inc"
.include "dp_forward.inc"
.include "dp_back.inc"
        cli     c8, #0
        cli     c9, #HB
        DP_SETUP
        DP_INIT
        DP_FORWARD
        DP_CLEARMAP
        DP_BACKTRACK
        DP_MERGE
        halt
