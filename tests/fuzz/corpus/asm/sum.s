; sum the column: c1 = 1 + 2 + ... + N (the example of docs/isa.md)
.ifndef N
.equ N 10                 ; default, overridden by -D N=...
.endif
.phase init
        cli c0, #N
        cli c1, #0
sum:    cadd c1, c1, c0   ; label on the same line as an instruction
        loop c0, sum
        halt
