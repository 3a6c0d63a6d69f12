; assembler: a .rept body holding 62 nested .rept blocks was re-scanned for
; its closing lines on every expansion, which the expansion budget did not
; count: 500 bytes took 52 s of CPU before the "more than 50000000 lines"
; error. Scanned lines now count against the budget (about 2 s).
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
