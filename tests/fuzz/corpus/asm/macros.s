; macros with parameters, unique local labels (\@) and nested expansion
.macro INC3 reg
        addi \reg, \reg, #3
.endm
.macro COUNT cnt, n
        cli \cnt, #\n
lp\@:   INC3 r1
        loop \cnt, lp\@
.endm
.macro TWICE what, a, b
        \what \a, \b
        \what \a, \b
.endm
        li r1, #0
        COUNT c2, 4
        COUNT c3, (2 + 1)
        TWICE COUNT, c4, 2
        st r1, [#10]
        halt
