; assembler (found by fuzzing): a .rept body holding 62 nested .rept blocks
; was re-scanned for its closing lines on every expansion, which the
; expansion budget did not count: 500 bytes took 52 s of CPU before the
; budget error. Scanned lines now count against the budget.
.rept 1000000
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.rept 1
.set X 1
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
.endr
halt
