; video lines in and out (two ports)
.equ ROW_L 0
.equ ROW_R 1
        cli c1, #0          ; line
        cli c2, #0          ; column
        cli c3, #4
lines:  vin #0, [#ROW_L], c1, c2
        vin #1, [#ROW_R], c1, c2
        ld r0, [#ROW_L]
        ld r1, [#ROW_R]
        sub r2, r0, r1
        st r2, [#2]
        vout #0, [#2], c1, c2
        caddi c1, c1, #1
        loop c3, lines
        halt
