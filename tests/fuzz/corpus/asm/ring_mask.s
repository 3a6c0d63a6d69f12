; shift ring, nested mask, status reduction
        pidx r0, #0
        rxl r1, r0, #1
        rxr r2, r0, #5
        cltui r0, #2
        mif
          addi r3, r1, #100
          rany c1
          ceqi r0, #0
          mif
            rxl r4, r3, #1
            rall c2
          mend
        melse
          xori r3, r2, #0x55
          rany c3
        mend
        mall
        ceq r1, r2
        tnot
        sett r5
        tc
        setc r6
        halt
