; Stand-alone forward pass: the host fills every PE's line buffers
; (R' at IMGR, L' at IMGL) and reads the pointer columns back from the
; external memory. Used by the firmware tests; the full program (dp.s)
; runs the same macros after its video re-layout.
.include "dp_init.inc"
.include "dp_forward.inc"
        DP_INIT
        DP_FORWARD
        halt
